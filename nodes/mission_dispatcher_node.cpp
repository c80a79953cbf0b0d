// The mission dispatcher: accepts, validates, publishes and tracks missions; signals loading.
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <csignal>

#include "swarm_transport/ros/common/connection_reaper.h"
#include "swarm_transport/ros/common/crash_trace.h"
#include "swarm_transport/ros/common/master_watch.h"
#include "swarm_transport/ros/dispatcher/mission_dispatcher.h"

namespace {

volatile std::sig_atomic_t stop_requested = 0;

}  // namespace

int main(int argc, char** argv) {
  swarm_transport::InstallCrashTrace("mission_dispatcher");
  // Our own SIGINT / SIGTERM handler: roscpp's would shut down before the dispatcher deletes its
  // ~instance parameter (a clean stop is no restart for the next start on this master).
  ros::init(argc, argv, "mission_dispatcher", ros::init_options::NoSigintHandler);
  std::signal(SIGINT, [](int) { stop_requested = 1; });
  std::signal(SIGTERM, [](int) { stop_requested = 1; });
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  // Before the set-up: a master restart stops the node, even one during its set-up.
  swarm_transport::MasterWatch watch;
  // roscpp keeps connections that dropped while they were set up (connection_reaper.h).
  swarm_transport::ConnectionReaper reaper;
  swarm_transport::MissionDispatcher dispatcher(nh, private_nh);
  if (!dispatcher.Initialize()) return watch.ExitCode(1);
  // ros::spin()'s loop (one thread, the global queue), ended by the signals above too.
  ros::CallbackQueue* queue = ros::getGlobalCallbackQueue();
  while (ros::ok() && stop_requested == 0) queue->callAvailable(ros::WallDuration(0.1));
  dispatcher.Shutdown();
  ros::shutdown();
  return watch.ExitCode(0);
}
