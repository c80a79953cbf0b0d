#include "swarm_transport/ros/common/mission_topics.h"

#include <algorithm>

#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

// Up to a dispatcher's whole table of live orders at once (a flood of hand-made ones is the
// dispatcher's to refuse: the robots take only the orders it admitted).
constexpr std::uint32_t kMissionQueue = 256;
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
                                        take_(ToMissionMessage(*event.getConstMessage()),
                                              SenderOf(event.getPublisherName()));
                                      })));
}

void MissionTopics::Subscribe(ros::NodeHandle nh, Take take) {
  take_ = std::move(take);
  Add<Robot_Freeze>(nh, names::kFreeze, kQueue);
  Add<Robot_Continue>(nh, names::kContinue, kQueue);
  Add<New_Mission>(nh, names::kMissionNew, kMissionQueue);
  Add<Update_Object>(nh, names::kObjectUpdate, kQueue);
  Add<Delete_Object>(nh, names::kObjectDelete, kQueue);
  Add<Mission_Event>(nh, names::kMissionEvent, kQueue);
  Add<Mission_Status>(nh, names::kMissionStatus, kStatusQueue);
}

void MissionTopics::Shutdown() {
  for (ros::Subscriber& sub : subs_) sub.shutdown();
}

void MissionPublishers::Advertise(ros::NodeHandle nh) {
  if (status_pub_) return;
  freeze_pub_ = nh.advertise<Robot_Freeze>(names::kFreeze, kQueue);
  continue_pub_ = nh.advertise<Robot_Continue>(names::kContinue, kQueue);
  update_pub_ = nh.advertise<Update_Object>(names::kObjectUpdate, kQueue);
  delete_pub_ = nh.advertise<Delete_Object>(names::kObjectDelete, kQueue);
  status_pub_ = nh.advertise<Mission_Status>(names::kMissionStatus, kStatusQueue);
  progress_pub_ = nh.advertise<Mission_Status>(names::kMissionProgress, kProgressQueue);
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

}  // namespace swarm_transport
