#include "swarm_transport/ros/dispatcher/order_publisher.h"

#include <iterator>
#include <utility>

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
                               std::function<bool(std::uint16_t)> queued, const char* node)
    : lockstep_(lockstep), queued_(std::move(queued)), node_(node) {
  if (lockstep_) {
    pub_ = nh.advertise<New_Mission>(names::kMissionNew, kOrderQueue, true);
  } else {
    pub_ = nh.advertise<New_Mission>(
        names::kMissionNew, kOrderQueue,
        [this](const ros::SingleSubscriberPublisher& listener) { OnListener(listener); });
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
  ForgetStarted();
  for (const auto& kv : published_) listener.publish(kv.second);
  if (!published_.empty()) {
    ROS_INFO("%s: sent the %zu order(s) still QUEUED to %s, which connected after them", node_,
             published_.size(), listener.getSubscriberName().c_str());
  }
}

void OrderPublisher::ForgetStarted() {
  for (auto it = published_.begin(); it != published_.end();) {
    it = queued_(it->first) ? std::next(it) : published_.erase(it);
  }
}

}  // namespace swarm_transport
