// One robot of the swarm: ~id, the shared /swarm configuration; lock-step a tick per
// perception, real time its own timeline.
#include "swarm_transport/ros/robot/robot_node.h"

#include <ros/ros.h>

#include "swarm_transport/ros/common/connection_reaper.h"
#include "swarm_transport/ros/common/crash_trace.h"
#include "swarm_transport/ros/common/master_watch.h"

int main(int argc, char** argv) {
  swarm_transport::InstallCrashTrace("robot");
  ros::init(argc, argv, "robot");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  // Before the set-up: a master restart stops the node, even one during its set-up.
  swarm_transport::MasterWatch watch;
  // roscpp keeps connections that dropped while they were set up (connection_reaper.h).
  swarm_transport::ConnectionReaper reaper;
  swarm_transport::RobotNode node(nh, private_nh);
  if (!node.Initialize()) return watch.ExitCode(1);
  const bool ticked = node.Spin();
  node.Shutdown();
  return watch.ExitCode(ticked ? 0 : 1);
}
