// The dispatcher's outlets (core::DispatcherOutlet): what its policy decided, carried out over
// ROS - statuses, orders, LOADED / UNLOADED, statists, the lock-step answer, its log.
#include <algorithm>

#include "swarm_transport/Delete_Object.h"
#include "swarm_transport/Delete_Robot.h"
#include "swarm_transport/Dispatcher_Answer.h"
#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/mission_resend.h"
#include "swarm_transport/ros/dispatcher/mission_dispatcher.h"

namespace swarm_transport {

using core::MissionPhase;

void MissionDispatcher::PublishStatus(const core::MissionSpec& spec, MissionPhase phase,
                                      const std::string& reason, std::uint64_t tick) {
  Mission_Status msg;
  msg.mission_id = spec.id;
  msg.state = static_cast<std::uint8_t>(phase);
  msg.reason = reason;
  msg.stamp = ros::Time::now();
  msg.tick = tick;
  msg.robots_assigned =
      static_cast<std::uint16_t>(std::min<std::size_t>(spec.Assigned().size(), 65535));
  if (spec.all_finite && !spec.LeaderOnly()) {
    msg.object_position_x = static_cast<float>(spec.object_centre.x);
    msg.object_position_y = static_cast<float>(spec.object_centre.y);
    msg.distance_to_target = static_cast<float>(core::Distance(spec.object_centre, spec.target));
  }
  status_pub_.publish(msg);
}

void MissionDispatcher::Order(const core::MissionSpec& spec, std::uint64_t start_tick) {
  orders_->Publish(spec, start_tick);
}

void MissionDispatcher::Rejected(const core::MissionSpec& spec, const std::string& reason) {
  PublishStatus(spec, MissionPhase::kRejected, reason);
}

void MissionDispatcher::Aborted(const core::MissionSpec& spec, const std::string& reason) {
  PublishStatus(spec, MissionPhase::kAborted, reason,
                policy_->has_swarm() ? policy_->swarm_tick() : 0);
  Delete_Object msg;
  msg.mission_id = spec.id;
  delete_pub_.publish(msg);
}

void MissionDispatcher::Event(const core::Signal& signal, const char* why) {
  // Not latched: a restarted dispatcher sends the owed LOADED/UNLOADED of its rebuilt missions
  // within a second of advertising the topic, before the robots' connections are made (the
  // soak lost it at every restart, and the mission stood in UNLOADING for good).
  AwaitListeners(event_pub_, kNode);
  event_pub_.publish(ToMsg(signal));
  ROS_INFO("%s: sent %s for mission %u (%s; from tick %llu)", kNode, SignalName(signal.kind),
           signal.mission_id, why, static_cast<unsigned long long>(signal.not_before_tick));
}

void MissionDispatcher::StatistUp(std::uint16_t statist_id, core::Vec2 at, int copies) {
  for (int copy = 0; copy < copies; ++copy) {
    statist_pub_.publish(StatistPosition(statist_id, at, static_cast<std::uint8_t>(copy)));
  }
}

void MissionDispatcher::StatistDown(std::uint16_t statist_id, int copies) {
  Delete_Robot gone;
  gone.robot_id = statist_id;
  for (int copy = 0; copy < copies; ++copy) {
    gone.sub_id = static_cast<std::uint8_t>(copy);
    statist_delete_pub_.publish(gone);
  }
}

void MissionDispatcher::Answer(const core::DispatcherAnswer& answer) {
  answer_pub_.publish(ToMsg(answer));
}

void MissionDispatcher::Log(bool warn, const std::string& text) {
  if (warn) {
    ROS_WARN("%s: %s", kNode, text.c_str());
  } else {
    ROS_INFO("%s: %s", kNode, text.c_str());
  }
}

}  // namespace swarm_transport
