// The simulator: a turtlesim-like world for the swarm, with real-time or lock-step clock.
#include <ros/ros.h>

#include <csignal>

#include "swarm_transport/ros/common/connection_reaper.h"
#include "swarm_transport/ros/common/crash_trace.h"
#include "swarm_transport/ros/common/master_watch.h"
#include "swarm_transport/ros/simulator/simulator.h"

int main(int argc, char** argv) {
  swarm_transport::InstallCrashTrace("simulator");
  // Our own SIGINT handler: roscpp's would silence rosconsole before the final summary.
  ros::init(argc, argv, "simulator", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, [](int) { swarm_transport::Simulator::RequestStop(); });
  std::signal(SIGTERM, [](int) { swarm_transport::Simulator::RequestStop(); });
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  // Before the set-up: a master restart stops the node, even one during its set-up.
  swarm_transport::MasterWatch watch;
  // roscpp keeps connections that dropped while they were set up (connection_reaper.h).
  swarm_transport::ConnectionReaper reaper;
  swarm_transport::Simulator simulator(nh, private_nh);
  if (!simulator.Initialize()) return watch.ExitCode(1);
  simulator.Run();
  simulator.Shutdown();
  ros::shutdown();
  return watch.ExitCode(0);
}
