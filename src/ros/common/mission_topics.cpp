#include "swarm_transport/ros/common/mission_topics.h"

#include <algorithm>
#include <type_traits>
#include <variant>

#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

// Up to a dispatcher's whole table of live orders at once, and a flood of hand-made ones (the
// dispatcher's to refuse: the robots take only the orders it admitted) that must not push one
// of its orders out of the queue of a robot starved of CPU meanwhile.
constexpr std::uint32_t kMissionQueue = 1024;
constexpr std::uint32_t kQueue = 20;
constexpr std::uint32_t kStatusQueue = 50;
constexpr std::uint32_t kProgressQueue = 10;
// A first leader waits at most this long for its subscribers (MissionPublishers::Ready).
constexpr double kPublishersWaitS = 5.0;

}  // namespace

template <typename M>
void MissionTopics::Add(ros::NodeHandle& nh, const char* topic, std::uint32_t queue_size) {
  subs_.push_back(nh.subscribe<M>(topic, queue_size,
                                  boost::function<void(const ros::MessageEvent<M const>&)>(
                                      [this](const ros::MessageEvent<M const>& event) {
                                        const M& msg = *event.getConstMessage();
                                        std::uint64_t start_tick = 0;
                                        if constexpr (std::is_same_v<M, New_Mission>) {
                                          start_tick = msg.start_tick;
                                        }
                                        take_(ToMissionMessage(msg), event.getPublisherName(),
                                              start_tick);
                                      })));
}

void MissionTopics::AddAll(ros::NodeHandle& nh, std::uint32_t queue_size) {
  const auto queue = [queue_size](std::uint32_t own) { return queue_size > 0 ? queue_size : own; };
  Add<Robot_Freeze>(nh, names::kFreeze, queue(kQueue));
  Add<Robot_Continue>(nh, names::kContinue, queue(kQueue));
  Add<New_Mission>(nh, names::kMissionNew, queue(kMissionQueue));
  Add<Update_Object>(nh, names::kObjectUpdate, queue(kQueue));
  Add<Delete_Object>(nh, names::kObjectDelete, queue(kQueue));
  Add<Mission_Event>(nh, names::kMissionEvent, queue(kQueue));
  Add<Mission_Status>(nh, names::kMissionStatus, queue(kStatusQueue));
}

void MissionTopics::Subscribe(ros::NodeHandle nh, Take take) {
  take_ = [take = std::move(take)](const core::MissionMessage& message,
                                   const std::string& publisher, std::uint64_t /*start_tick*/) {
    take(message, SenderOf(publisher));
  };
  AddAll(nh, 0);
}

void MissionTopics::SubscribeFrom(ros::NodeHandle nh, TakeFrom take, std::uint32_t queue_size) {
  take_ = std::move(take);
  AddAll(nh, queue_size);
}

void MissionTopics::Shutdown() {
  for (ros::Subscriber& sub : subs_) sub.shutdown();
}

bool MissionTopics::AllConnected(const TopicNodeCounts& graph,
                                 const std::vector<std::string>& only) const {
  for (const ros::Subscriber& sub : subs_) {
    if (!only.empty() && std::find(only.begin(), only.end(), sub.getTopic()) == only.end())
      continue;
    if (!graph.AllConnected(sub)) return false;
  }
  return true;
}

void MissionPublishers::Advertise(ros::NodeHandle nh, std::uint32_t queue_size) {
  if (status_pub_) return;
  const auto queue = [queue_size](std::uint32_t own) { return queue_size > 0 ? queue_size : own; };
  freeze_pub_ = nh.advertise<Robot_Freeze>(names::kFreeze, queue(kQueue));
  continue_pub_ = nh.advertise<Robot_Continue>(names::kContinue, queue(kQueue));
  update_pub_ = nh.advertise<Update_Object>(names::kObjectUpdate, queue(kQueue));
  delete_pub_ = nh.advertise<Delete_Object>(names::kObjectDelete, queue(kQueue));
  status_pub_ = nh.advertise<Mission_Status>(names::kMissionStatus, queue(kStatusQueue));
  progress_pub_ = nh.advertise<Mission_Status>(names::kMissionProgress, queue(kProgressQueue));
  since_ = ros::WallTime::now();
  ready_ = false;
  if (!QueryTopicNodeCounts(&expected_, true)) expected_ = TopicNodeCounts();
}

bool MissionPublishers::Ready() {
  if (!status_pub_ || ready_) return true;
  // At least one subscriber (the simulator's relay) even if the master did not answer.
  const auto connected = [this](const ros::Publisher& pub) {
    return pub.getNumSubscribers() >=
           std::max<std::uint32_t>(1, expected_.Subscribers(pub.getTopic()));
  };
  ready_ = (connected(freeze_pub_) && connected(continue_pub_) && connected(update_pub_) &&
            connected(delete_pub_) && connected(status_pub_)) ||
           ros::WallTime::now() - since_ > ros::WallDuration(kPublishersWaitS);
  return ready_;
}

bool MissionPublishers::Publish(const Tick_Answer& m) {
  const bool any = !m.object_updates.empty() || !m.freezes.empty() || !m.continues.empty() ||
                   !m.object_deletes.empty() || !m.statuses.empty() || !m.progress.empty();
  if (!any) return true;
  if (!status_pub_) return false;
  for (const auto& u : m.object_updates) update_pub_.publish(u);
  for (const auto& f : m.freezes) freeze_pub_.publish(f);
  for (const auto& c : m.continues) continue_pub_.publish(c);
  for (const auto& d : m.object_deletes) delete_pub_.publish(d);
  for (const auto& st : m.statuses) status_pub_.publish(st);
  for (const auto& st : m.progress) progress_pub_.publish(st);
  return true;
}

void MissionPublishers::Publish(const core::MissionMessage& message) {
  std::visit(core::Overloaded{
                 [this](const core::ObjectUpdate& m) { update_pub_.publish(ToMsg(m)); },
                 [this](const core::ObjectDelete& m) { delete_pub_.publish(ToMsg(m)); },
                 [this](const core::Freeze& m) { freeze_pub_.publish(ToMsg(m)); },
                 [this](const core::Continue& m) { continue_pub_.publish(ToMsg(m)); },
                 [](const auto&) {},  // the dispatcher's own topics
             },
             message);
}

bool MissionPublishers::AllConnected(const TopicNodeCounts& graph) const {
  for (const ros::Publisher* pub :
       {&status_pub_, &progress_pub_, &update_pub_, &delete_pub_, &freeze_pub_, &continue_pub_}) {
    if (!graph.AllConnected(*pub)) return false;
  }
  return true;
}

}  // namespace swarm_transport
