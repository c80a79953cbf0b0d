// The core machine of a swarm on real robots: the robots' /flock/position as /flock/world_poses.
#include <ros/ros.h>

#include "swarm_transport/ros/bases/positions_relay.h"
#include "swarm_transport/ros/common/connection_reaper.h"
#include "swarm_transport/ros/common/crash_trace.h"
#include "swarm_transport/ros/common/master_watch.h"

int main(int argc, char** argv) {
  swarm_transport::InstallCrashTrace("positions");
  ros::init(argc, argv, "positions");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  swarm_transport::MasterWatch watch;
  // roscpp keeps connections that dropped while they were set up (connection_reaper.h).
  swarm_transport::ConnectionReaper reaper;
  swarm_transport::PositionsRelay relay(nh, private_nh);
  if (!relay.Initialize()) return watch.ExitCode(1);
  ros::spin();
  ros::shutdown();
  return watch.ExitCode(0);
}
