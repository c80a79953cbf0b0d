// The recorder: swarm counts and mission metrics of a run, as CSV files and /flock/stats.
#include <ros/ros.h>

#include <csignal>

#include "swarm_transport/ros/common/connection_reaper.h"
#include "swarm_transport/ros/common/crash_trace.h"
#include "swarm_transport/ros/common/master_watch.h"
#include "swarm_transport/ros/recorder/recorder.h"

int main(int argc, char** argv) {
  swarm_transport::InstallCrashTrace("recorder");
  // Our own SIGINT / SIGTERM handler: roscpp's would shut down before the files are closed.
  ros::init(argc, argv, "recorder", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, [](int) { swarm_transport::Recorder::RequestStop(); });
  std::signal(SIGTERM, [](int) { swarm_transport::Recorder::RequestStop(); });
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  // Before the set-up: a master restart stops the node, even one during its set-up.
  swarm_transport::MasterWatch watch;
  // roscpp keeps connections that dropped while they were set up (connection_reaper.h).
  swarm_transport::ConnectionReaper reaper;
  swarm_transport::Recorder recorder(nh, private_nh);
  if (!recorder.Initialize()) return watch.ExitCode(1);
  recorder.Run();
  recorder.Shutdown();
  ros::shutdown();
  return watch.ExitCode(0);
}
