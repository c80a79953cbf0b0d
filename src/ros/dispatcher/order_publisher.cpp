#include "swarm_transport/ros/dispatcher/order_publisher.h"

#include <algorithm>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/graph.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

// Before publishing a new order or an event, wait at most this long (wall) for every node the
// master lists as a subscriber of its topic to be connected.
constexpr double kListenerWaitS = 1.0;
// Its queue holds a whole table of live orders published at once (a flood's admitted ones).
constexpr std::uint32_t kOrderQueue = 256;

}  // namespace

void AwaitListeners(const ros::Publisher& pub, const char* node) {
  // A node that subscribed but is not connected yet (start-up, a loaded machine) would get
  // the latched order late: a lock-step run would not repeat.
  if (!AwaitSubscribers(pub, kListenerWaitS)) {
    ROS_WARN("%s: not every subscriber of %s is connected after %.1f s; publishing anyway", node,
             pub.getTopic().c_str(), kListenerWaitS);
  }
}

OrderPublisher::OrderPublisher(ros::NodeHandle nh, bool lockstep,
                               std::function<bool(std::uint16_t)> queued, const char* node,
                               Unreachable unreachable)
    : lockstep_(lockstep),
      queued_(std::move(queued)),
      node_(node),
      unreachable_changed_(std::move(unreachable)) {
  if (lockstep_) {
    pub_ = nh.advertise<New_Mission>(names::kMissionNew, kOrderQueue, true);
  } else {
    pub_ = nh.advertise<New_Mission>(
        names::kMissionNew, kOrderQueue,
        [this](const ros::SingleSubscriberPublisher& listener) { OnListener(listener); },
        [this](const ros::SingleSubscriberPublisher& listener) { OnListenerGone(listener); });
  }
}

void OrderPublisher::Publish(const core::MissionSpec& spec, std::uint64_t start_tick) {
  AwaitListeners(pub_, node_);
  New_Mission order = ToNewMission(spec);
  order.start_tick = start_tick;
  pub_.publish(order);
  if (!lockstep_) published_[spec.id] = order;
}

void OrderPublisher::OnListener(const ros::SingleSubscriberPublisher& listener) {
  const core::Sender sender = SenderOf(listener.getSubscriberName());
  if (sender.kind == core::SenderKind::kRobot) {
    ++connections_[sender.robot_id];
    std::set<std::uint16_t> unreachable = unreachable_;
    if (unreachable.erase(sender.robot_id) > 0) {
      ROS_INFO("%s: robot %u's process is connected: it may be picked", node_, sender.robot_id);
      SetUnreachable(std::move(unreachable));
    }
  }
  ForgetStarted();
  for (const auto& kv : published_) listener.publish(kv.second);
  if (!published_.empty()) {
    ROS_INFO("%s: sent the %zu order(s) still QUEUED to %s, which connected after them", node_,
             published_.size(), listener.getSubscriberName().c_str());
  }
}

void OrderPublisher::OnListenerGone(const ros::SingleSubscriberPublisher& listener) {
  const core::Sender sender = SenderOf(listener.getSubscriberName());
  if (sender.kind != core::SenderKind::kRobot) return;
  int& count = connections_[sender.robot_id];
  count = std::max(0, count - 1);
  if (count == 0 && unreachable_.count(sender.robot_id) == 0) {
    ROS_INFO("%s: robot %u's process is gone from %s: no order picks it until it connects again",
             node_, sender.robot_id, pub_.getTopic().c_str());
    std::set<std::uint16_t> unreachable = unreachable_;
    unreachable.insert(sender.robot_id);
    SetUnreachable(std::move(unreachable));
  }
}

void OrderPublisher::RefreshUnreachable() {
  std::vector<std::string> nodes;
  if (lockstep_ || !QuerySubscriberNodes(pub_.getTopic(), &nodes)) return;
  std::set<std::uint16_t> registered;  // listed by the master, not connected (yet)
  for (const std::string& name : nodes) {
    const core::Sender sender = SenderOf(name);
    if (sender.kind != core::SenderKind::kRobot) continue;
    const auto it = connections_.find(sender.robot_id);
    if (it == connections_.end() || it->second == 0) registered.insert(sender.robot_id);
  }
  // Gone (connected once, not now) or registered and not connected yet.
  std::set<std::uint16_t> unreachable = registered;
  for (const auto& kv : connections_) {
    if (kv.second == 0) unreachable.insert(kv.first);
  }
  if (unreachable != unreachable_) {
    std::string ids;
    for (std::uint16_t id : registered) ids += (ids.empty() ? "" : ", ") + std::to_string(id);
    if (!ids.empty()) {
      ROS_INFO("%s: robot process(es) %s subscribe %s but are not connected yet: not picked", node_,
               ids.c_str(), pub_.getTopic().c_str());
    }
    SetUnreachable(std::move(unreachable));
  }
}

void OrderPublisher::SetUnreachable(std::set<std::uint16_t> unreachable) {
  unreachable_ = std::move(unreachable);
  if (unreachable_changed_) unreachable_changed_(unreachable_);
}

void OrderPublisher::ForgetStarted() {
  for (auto it = published_.begin(); it != published_.end();) {
    it = queued_(it->first) ? std::next(it) : published_.erase(it);
  }
}

}  // namespace swarm_transport
