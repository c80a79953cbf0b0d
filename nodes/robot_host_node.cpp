// Many robots in one process (ids [~from, ~to)), each as if it were its own robot node.
#include <ros/ros.h>

#include "swarm_transport/ros/common/connection_reaper.h"
#include "swarm_transport/ros/common/crash_trace.h"
#include "swarm_transport/ros/common/master_watch.h"
#include "swarm_transport/ros/robot/robot_host.h"

int main(int argc, char** argv) {
  swarm_transport::InstallCrashTrace("robot_host");
  ros::init(argc, argv, "robot_host");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  // Before the set-up: a master restart stops the node, even one during its set-up.
  swarm_transport::MasterWatch watch;
  // roscpp keeps connections that dropped while they were set up (connection_reaper.h).
  swarm_transport::ConnectionReaper reaper;
  swarm_transport::RobotHost host(nh, private_nh);
  if (!host.Initialize()) return watch.ExitCode(1);
  host.Spin();
  host.Shutdown();
  return watch.ExitCode(0);
}
