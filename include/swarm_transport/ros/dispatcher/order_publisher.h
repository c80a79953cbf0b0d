// The dispatcher's orders on /flock/mission/new, and who gets them when.
#ifndef SWARM_TRANSPORT_ROS_ORDER_PUBLISHER_H_
#define SWARM_TRANSPORT_ROS_ORDER_PUBLISHER_H_

#include <ros/ros.h>

#include <cstdint>
#include <functional>
#include <map>
#include <set>

#include "swarm_transport/New_Mission.h"
#include "swarm_transport/core/mission.h"

namespace swarm_transport {

// A robot (or `rostopic echo`) connecting later still gets an order while its mission waits
// to start. Lock-step latches the last one (its robots take orders from their rounds). Real
// time sends every order whose mission is still QUEUED to each subscriber as it connects (a
// robot process started late or again, the recorder): a robot that connects after its order
// missed it while audible on the radio, so its mission's members never lost it and their
// GATHERING waited for it for good (the soak). The order of a mission that has started does not
// go (a process killed and started again under a member's id must not run it from QUEUED beside
// the robots that carry it).
//
// Real time, it also keeps which robots' own processes (nodes /robot_<id>/robot) are connected:
// a robot whose process was connected once and is not now (killed; started again and not
// connected yet), or whose process the master lists as a subscriber but is not connected yet
// (start-up on a loaded machine: a robot picked then missed its order, yet was heard), is
// unreachable until its process connects, and `unreachable` is called with the set at every
// change (the dispatcher picks no robot among them: DispatcherPolicy::SetUnreachable). Robots
// without a process of their own (a robot host's, lock-step) are never counted unreachable.
class OrderPublisher {
 public:
  using Unreachable = std::function<void(const std::set<std::uint16_t>&)>;
  // `queued(id)`: mission `id` is still QUEUED. `node`: the name in log lines.
  OrderPublisher(ros::NodeHandle nh, bool lockstep, std::function<bool(std::uint16_t)> queued,
                 const char* node, Unreachable unreachable = nullptr);
  // Waits (at most kListenerWaitS) until every registered subscriber is connected, then
  // publishes.
  void Publish(const core::MissionSpec& spec, std::uint64_t start_tick);
  // Forgets the published orders whose missions left QUEUED: a robot that connects from now on
  // is too late for them (quiet on the radio until its order topic is connected, it is lost for
  // the mission's members after lost_after_s, and the mission goes on without it).
  void ForgetStarted();
  // Real time: asks the master which robot processes subscribe the orders, so that one not
  // connected yet counts as unreachable (before a submission picks robots).
  void RefreshUnreachable();

 private:
  void OnListener(const ros::SingleSubscriberPublisher& listener);
  void OnListenerGone(const ros::SingleSubscriberPublisher& listener);

  bool lockstep_;
  std::function<bool(std::uint16_t)> queued_;
  const char* node_;
  ros::Publisher pub_;
  std::map<std::uint16_t, New_Mission> published_;  // real time: published, still QUEUED
  Unreachable unreachable_changed_;
  void SetUnreachable(std::set<std::uint16_t> unreachable);

  std::map<std::uint16_t, int> connections_;  // a robot's own process: its connections now
  std::set<std::uint16_t> unreachable_;
};

// Before a new order or an event: waits (at most kListenerWaitS) until every registered
// subscriber of pub's topic is connected; a warning when not.
void AwaitListeners(const ros::Publisher& pub, const char* node);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_ORDER_PUBLISHER_H_
