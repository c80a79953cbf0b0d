// A restarted mission dispatcher's table, rebuilt from the robots [issue 29]: the first leaders
// re-send their missions' latest statuses (and the orders they still carry) on request.
#ifndef SWARM_TRANSPORT_ROS_DISPATCHER_REBUILD_H_
#define SWARM_TRANSPORT_ROS_DISPATCHER_REBUILD_H_

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <cstdint>

#include "swarm_transport/Mission_Resend_Request.h"
#include "swarm_transport/Mission_Resent.h"
#include "swarm_transport/core/dispatcher_policy.h"
#include "swarm_transport/ros/common/wall_throttle.h"

namespace swarm_transport {

// Real time only (a lock-step restart starts empty). Run() asks the first leaders on the
// latched /flock/mission/resend_request and takes their answers on /flock/mission/resent
// before anything else, in its own callback queue: for at least kRebuildWaitS of wall time and
// up to kRebuildMaxS, until every robot's connection to it is made and one more request went
// over them. Later answers (to a restarted recorder's request) are taken in the spin thread.
class DispatcherRebuild {
 public:
  // `policy` and `node` (the name in log lines) outlive it.
  DispatcherRebuild(ros::NodeHandle nh, core::DispatcherPolicy* policy, const char* node);
  // Blocks until the table is rebuilt (see above).
  void Run();
  // A restarted dispatcher hears of a live mission it did not rebuild (its first leader's answer
  // was lost while the connections to the first leaders were still being made, on a loaded
  // machine): it asks the first leaders again, at most once a second. Without it, such a
  // mission never got its UNLOADED and stood in UNLOADING for good.
  void AskAgain(std::uint16_t mission_id);
  void Stop() { resent_timer_.stop(); }

 private:
  void OnResent(const ros::MessageEvent<Mission_Resent const>& event);
  void Request();

  ros::NodeHandle nh_;
  core::DispatcherPolicy* policy_;
  const char* node_;
  ros::CallbackQueue resent_queue_;  // the re-sent statuses, taken first
  ros::Subscriber resent_sub_;
  ros::Publisher request_pub_;      // the latched Mission_Resend_Request
  Mission_Resend_Request request_;  // ... its latest (numbered from 1)
  ros::WallTime next_ask_;          // AskAgain: not before
  ros::WallTimer resent_timer_;
  WarnThrottle foreign_warning_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_DISPATCHER_REBUILD_H_
