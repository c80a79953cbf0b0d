// The hardware stand-in: kinematic bases with odometry, for robots deployed as on hardware.
#include <ros/ros.h>

#include "swarm_transport/ros/bases/bases.h"
#include "swarm_transport/ros/common/connection_reaper.h"
#include "swarm_transport/ros/common/crash_trace.h"
#include "swarm_transport/ros/common/master_watch.h"

int main(int argc, char** argv) {
  swarm_transport::InstallCrashTrace("bases");
  ros::init(argc, argv, "bases");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  swarm_transport::MasterWatch watch;
  // roscpp keeps connections that dropped while they were set up (connection_reaper.h).
  swarm_transport::ConnectionReaper reaper;
  swarm_transport::Bases bases(nh, private_nh);
  if (!bases.Initialize()) return watch.ExitCode(1);
  bases.Run();
  ros::shutdown();
  return watch.ExitCode(0);
}
