// Missions outlive their dispatcher and their record its recorder (issue 29, docs/reliability.md):
// a real-time first leader remembers the latest status it published for each mission it leads
// or led (with the order it carried) and re-sends them on /flock/mission/resent when a restarted
// dispatcher or recorder asks on /flock/mission/resend_request. Only first leaders subscribe the
// request, so one request costs one message per first leader and mission, whatever the swarm's
// size. A node knows it was restarted from its ~instance parameter (WasStartedBefore), which a
// clean stop deletes (ForgetInstance).
#ifndef SWARM_TRANSPORT_ROS_MISSION_RESEND_H_
#define SWARM_TRANSPORT_ROS_MISSION_RESEND_H_

#include <ros/ros.h>

#include <cstdint>
#include <map>
#include <mutex>
#include <string>

#include "swarm_transport/Mission_Resend_Request.h"
#include "swarm_transport/Mission_Resent.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/core/mission.h"

namespace swarm_transport {

// A first leader's memory of its missions' latest statuses and its answers to requests. Its
// methods may be called from any thread (a host's workers and its spinner).
class MissionResender {
 public:
  // Missions remembered; the one heard of longest ago goes first.
  static constexpr std::size_t kMaxMissions = 64;
  // `status` is the latest of its mission, with the order the robot carries (may be null).
  void Remember(const Mission_Status& status, const core::MissionSpec* order);
  // Mission `mission_id` ended (its DONE or ABORTED heard from the robot that ended it, or the
  // dispatcher): a phase remembered before is forgotten, so that a robot that led it once (a
  // first leader lost and replaced) never re-sends it live to a restarted dispatcher. Its own
  // DONE or ABORTED is kept.
  void Ended(std::uint16_t mission_id);
  // Answers requests from now on (the first call subscribes and advertises on `nh`).
  void Start(ros::NodeHandle nh);
  std::size_t remembered() const;
  bool Remembers(std::uint16_t mission_id) const;

 private:
  void OnRequest(const Mission_Resend_Request::ConstPtr& request);

  mutable std::mutex mutex_;
  std::map<std::uint16_t, Mission_Resent> latest_;
  std::map<std::uint16_t, std::uint64_t> heard_;  // ... in the order of Remember calls
  std::uint64_t remembers_ = 0;
  std::map<std::string, std::uint32_t> answered_;  // per requester, its latest request answered
  ros::Publisher pub_;
  ros::Subscriber sub_;
};

// True when node `private_nh` ran before on this master with the same `what` (its ~instance
// parameter is set and names it: a recorder's run directory); sets it for the next start
// (pid, wall time and `what`).
bool WasStartedBefore(const ros::NodeHandle& private_nh, const std::string& what = "");
// A clean stop (SIGINT, SIGTERM: roslaunch, Ctrl-C) deletes ~instance, so that the next start
// on this master (a test launching a swarm again) is no restart; a node killed (SIGKILL) leaves
// it. Does nothing once roscpp is shut down.
void ForgetInstance(const ros::NodeHandle& private_nh);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_MISSION_RESEND_H_
