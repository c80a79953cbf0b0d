#include "swarm_transport/ros/simulator/mission_mirror.h"

#include <algorithm>
#include <vector>

#include "swarm_transport/Mission_Objects.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

// A flood of 500 hand-made orders must not push an order of the dispatcher out.
constexpr std::uint32_t kMissionQueue = 1024;

}  // namespace

MissionMirror::MissionMirror(core::Admission admission, const sim::World2D* world)
    : admission_(admission), world_(world) {}

void MissionMirror::Connect(ros::NodeHandle nh, bool lockstep, std::uint32_t queue) {
  objects_pub_ = nh.advertise<Mission_Objects>(names::kObjects, queue);
  if (!lockstep) {
    // Lock-step takes orders in through the relay, at the tick the robots take them.
    mission_new_sub_ =
        nh.subscribe(names::kMissionNew, kMissionQueue, &MissionMirror::OnMissionNew, this);
  }
  object_update_sub_ =
      nh.subscribe(names::kObjectUpdate, kMissionQueue, &MissionMirror::OnObjectUpdate, this);
  // Each mission's phase, for the status line in rviz (lock-step: the simulator's own relay).
  status_sub_ =
      nh.subscribe(names::kMissionStatus, kMissionQueue, &MissionMirror::OnMissionStatus, this);
  object_delete_sub_ =
      nh.subscribe(names::kObjectDelete, kMissionQueue, &MissionMirror::OnObjectDelete, this);
}

void MissionMirror::Shutdown() {
  mission_new_sub_.shutdown();
  object_update_sub_.shutdown();
  status_sub_.shutdown();
  object_delete_sub_.shutdown();
  objects_pub_.shutdown();
}

void MissionMirror::Register(const New_Mission& order) {
  const std::string why = sim::RegisterMission(ToMissionSpec(order), *world_, &missions_);
  if (!why.empty()) {
    ROS_DEBUG("simulator: ignored New_Mission %u: %s", order.mission_id, why.c_str());
  }
}

void MissionMirror::UpdateObject(std::uint16_t mission_id, core::Vec2 centre) {
  sim::UpdateMissionObject(mission_id, centre, *world_, &missions_);
}

void MissionMirror::PublishObjects(std::uint64_t tick) {
  if (objects_pub_.getNumSubscribers() == 0) return;
  Mission_Objects objects;
  objects.tick = tick;
  for (const auto& entry : missions_) {
    const sim::LiveMission& m = entry.second;
    if (m.object_size.x <= 0.0 && m.object_size.y <= 0.0) continue;  // leader-only
    objects.mission_ids.push_back(entry.first);
    objects.x.push_back(static_cast<float>(m.object_position.x));
    objects.y.push_back(static_cast<float>(m.object_position.y));
    objects.size_x.push_back(static_cast<float>(m.object_size.x));
    objects.size_y.push_back(static_cast<float>(m.object_size.y));
  }
  objects_pub_.publish(objects);
}

// Real time: the mirror follows what the robots act on, with the robots' rules.
void MissionMirror::OnMissionNew(const ros::MessageEvent<New_Mission const>& event) {
  if (!core::MayOrder(admission_, SenderOf(event.getPublisherName()))) return;
  Register(*event.getConstMessage());
}

void MissionMirror::OnObjectUpdate(const ros::MessageEvent<Update_Object const>& event) {
  const Update_Object& msg = *event.getConstMessage();
  if (!MayReport(msg.mission_id, event.getPublisherName())) return;
  UpdateObject(msg.mission_id, {msg.object_position_x, msg.object_position_y});
}

void MissionMirror::OnObjectDelete(const ros::MessageEvent<Delete_Object const>& event) {
  if (!MayReport(event.getConstMessage()->mission_id, event.getPublisherName())) return;
  missions_.erase(event.getConstMessage()->mission_id);
}

void MissionMirror::OnMissionStatus(const ros::MessageEvent<Mission_Status const>& event) {
  const Mission_Status& msg = *event.getConstMessage();
  auto it = missions_.find(msg.mission_id);
  // A REJECTED names an order refused, which may carry a live mission's id (a duplicate).
  if (it == missions_.end() || msg.state >= Mission_Status::REJECTED ||
      !MayReport(msg.mission_id, event.getPublisherName())) {
    return;
  }
  it->second.phase = std::max<int>(it->second.phase, msg.state);
}

bool MissionMirror::MayReport(std::uint16_t mission_id, const std::string& publisher) const {
  const core::Sender from = SenderOf(publisher);
  const auto it = missions_.find(mission_id);
  if (from.kind != core::SenderKind::kRobot || it == missions_.end()) {
    return core::MayReport(nullptr, from);
  }
  const std::vector<std::uint16_t>& members = it->second.members;
  return std::binary_search(members.begin(), members.end(), from.robot_id);
}

}  // namespace swarm_transport
