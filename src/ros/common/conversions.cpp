#include "swarm_transport/ros/common/conversions.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {

core::Neighbour ToNeighbour(const Robot_Position& msg) {
  core::Neighbour n;
  n.id = msg.robot_id;
  n.sub_id = msg.sub_id;
  n.type = msg.type;
  n.position = {msg.pos_x, msg.pos_y};
  n.heading = core::Angle(msg.angle);
  return n;
}

Robot_Position ToRobotPosition(std::uint16_t id, const core::Pose2& pose, std::uint8_t sub_id,
                               std::uint8_t type) {
  Robot_Position msg;
  msg.robot_id = id;
  msg.sub_id = sub_id;
  msg.type = type;
  msg.pos_x = static_cast<float>(pose.position.x);
  msg.pos_y = static_cast<float>(pose.position.y);
  msg.angle = static_cast<float>(pose.heading.degrees());
  // float rounding may turn 359.9999999 into 360.0f: keep the [0, 360) promise.
  if (msg.angle >= 360.0f) msg.angle = 0.0f;
  return msg;
}

core::Pose2 ToPose2(const Pose& msg) {
  return core::Pose2{{msg.x, msg.y}, core::Angle::FromRadians(msg.theta)};
}

Pose ToPoseMsg(const core::Pose2& pose, const core::Velocity& velocity) {
  Pose msg;
  msg.x = static_cast<float>(pose.position.x);
  msg.y = static_cast<float>(pose.position.y);
  double theta = pose.heading.radians();
  if (theta > M_PI) theta -= 2.0 * M_PI;
  msg.theta = static_cast<float>(theta);
  msg.linear_velocity = static_cast<float>(velocity.linear);
  msg.angular_velocity = static_cast<float>(velocity.angular);
  return msg;
}

core::Velocity ToVelocity(const geometry_msgs::Twist& msg) {
  return core::Velocity{msg.linear.x, msg.angular.z};
}

geometry_msgs::Twist ToTwist(const core::Velocity& velocity) {
  geometry_msgs::Twist msg;
  msg.linear.x = velocity.linear;
  msg.angular.z = velocity.angular;
  return msg;
}

bool IsFinite(const Robot_Position& msg) {
  return std::isfinite(msg.pos_x) && std::isfinite(msg.pos_y) && std::isfinite(msg.angle);
}

bool IsFinite(const geometry_msgs::Twist& msg) {
  return std::isfinite(msg.linear.x) && std::isfinite(msg.linear.y) &&
         std::isfinite(msg.linear.z) && std::isfinite(msg.angular.x) &&
         std::isfinite(msg.angular.y) && std::isfinite(msg.angular.z);
}

Mission_Event ToEventMsg(const core::DueSignal& due) {
  Mission_Event msg;
  msg.mission_id = due.mission_id;
  msg.event = static_cast<std::uint8_t>(due.kind);
  msg.not_before_tick = due.not_before_tick;
  return msg;
}

core::MissionMessage ToMissionMessage(const New_Mission& msg) { return ToMissionSpec(msg); }

core::MissionMessage ToMissionMessage(const Update_Object& msg) {
  return core::ObjectUpdate{msg.mission_id, {msg.object_position_x, msg.object_position_y}};
}

core::MissionMessage ToMissionMessage(const Delete_Object& msg) {
  return core::ObjectDelete{msg.mission_id};
}

core::MissionMessage ToMissionMessage(const Robot_Freeze& msg) {
  return core::Freeze{msg.robot_index_from, msg.robot_index_to};
}

core::MissionMessage ToMissionMessage(const Robot_Continue& msg) {
  return core::Continue{msg.robot_index_from, msg.robot_index_to};
}

core::MissionMessage ToMissionMessage(const Mission_Event& msg) {
  return core::Signal{msg.mission_id, static_cast<core::MissionEventKind>(msg.event),
                      msg.not_before_tick};
}

core::MissionMessage ToMissionMessage(const Mission_Status& msg) {
  return core::PhaseStatus{msg.mission_id, static_cast<core::MissionPhase>(msg.state)};
}

std::vector<core::MissionMessage> ToMissionMessages(const Neighbors& round) {
  std::vector<core::MissionMessage> out;
  out.reserve(round.missions.size() + round.object_updates.size() + round.object_deletes.size() +
              round.freezes.size() + round.continues.size() + round.mission_events.size() +
              round.statuses.size());
  const auto add = [&out](const auto& list) {
    for (const auto& m : list) out.push_back(ToMissionMessage(m));
  };
  add(round.missions);
  add(round.object_updates);
  add(round.object_deletes);
  add(round.freezes);
  add(round.continues);
  add(round.mission_events);
  add(round.statuses);
  return out;
}

core::MissionSpec ToMissionSpec(const New_Mission& msg) {
  core::MissionSpec spec;
  spec.id = msg.mission_id;
  spec.range_from = msg.robot_index_from;
  spec.range_to = msg.robot_index_to;
  spec.robot_ids = msg.robot_ids;
  spec.leader_number = msg.leader_number;
  spec.object_centre = {msg.object_position_x, msg.object_position_y};
  spec.object_size = {msg.object_size_x, msg.object_size_y};
  spec.target = {msg.target_x, msg.target_y};
  spec.transport_mode = msg.transport_mode;
  spec.robot_count = msg.robot_count;
  spec.recruit = msg.recruit;
  spec.leader_ids = msg.leader_ids;
  spec.all_finite = std::isfinite(msg.object_position_x) && std::isfinite(msg.object_position_y) &&
                    std::isfinite(msg.object_size_x) && std::isfinite(msg.object_size_y) &&
                    std::isfinite(msg.target_x) && std::isfinite(msg.target_y);
  return spec;
}

New_Mission ToNewMission(const core::MissionSpec& spec) {
  New_Mission msg;
  msg.mission_id = spec.id;
  msg.robot_index_from = spec.range_from;
  msg.robot_index_to = spec.range_to;
  msg.robot_ids = spec.robot_ids;
  // leader_number is uint8 on the wire; specs read from messages or mission files fit it.
  msg.leader_number = static_cast<std::uint8_t>(std::min(std::max(spec.leader_number, 0), 255));
  msg.object_position_x = static_cast<float>(spec.object_centre.x);
  msg.object_position_y = static_cast<float>(spec.object_centre.y);
  msg.object_size_x = static_cast<float>(spec.object_size.x);
  msg.object_size_y = static_cast<float>(spec.object_size.y);
  msg.target_x = static_cast<float>(spec.target.x);
  msg.target_y = static_cast<float>(spec.target.y);
  msg.transport_mode = spec.transport_mode;
  msg.robot_count = spec.robot_count;
  msg.recruit = spec.recruit;
  msg.leader_ids = spec.leader_ids;
  return msg;
}

Neighbors RadioRoundMessage(std::uint64_t tick, double sim_time, const sim::Robot& robot,
                            const sim::RadioRound& round, const std::vector<Robot_Position>& truth,
                            const std::vector<Robot_Position>& extras) {
  Neighbors msg;
  msg.tick = tick;
  msg.sim_time = sim_time;
  msg.pose = ToPoseMsg(robot.pose, robot.last_velocity);
  msg.robots.reserve(round.in_range.size() + round.extras.size());
  for (std::size_t j : round.in_range) msg.robots.push_back(truth[j]);
  for (std::size_t e : round.extras) msg.robots.push_back(extras[e]);
  msg.relayed.reserve(round.chain.size());
  for (std::size_t j : round.chain) msg.relayed.push_back(truth[j]);
  msg.mission_peers.reserve(round.peers.size());
  for (std::size_t j : round.peers) msg.mission_peers.push_back(truth[j]);
  return msg;
}

Tick_Answer ToAnswerMessages(const core::MissionOutbox& outbox,
                             const std::vector<core::StatusReport>& progress, std::uint64_t tick,
                             const ros::Time& stamp) {
  const auto status = [tick, &stamp](const core::StatusReport& r) {
    Mission_Status m;
    m.mission_id = r.mission_id;
    m.state = static_cast<std::uint8_t>(r.phase);
    m.reason = r.reason;
    m.stamp = stamp;
    m.tick = tick;
    m.robots_assigned = r.assigned;
    m.robots_inside = r.inside;
    m.object_position_x = static_cast<float>(r.object.x);
    m.object_position_y = static_cast<float>(r.object.y);
    m.distance_to_target = static_cast<float>(r.distance_to_target);
    return m;
  };
  Tick_Answer m;
  if (outbox.update_object) {
    Update_Object u;
    u.mission_id = outbox.update_object->first;
    u.object_position_x = static_cast<float>(outbox.update_object->second.x);
    u.object_position_y = static_cast<float>(outbox.update_object->second.y);
    m.object_updates.push_back(u);
  }
  for (const auto& run : outbox.freeze) {
    Robot_Freeze f;
    f.robot_index_from = run.first;
    f.robot_index_to = run.second;
    m.freezes.push_back(f);
  }
  for (const auto& run : outbox.resume) {
    Robot_Continue c;
    c.robot_index_from = run.first;
    c.robot_index_to = run.second;
    m.continues.push_back(c);
  }
  if (outbox.delete_object) {
    Delete_Object d;
    d.mission_id = *outbox.delete_object;
    m.object_deletes.push_back(d);
  }
  for (const core::StatusReport& r : outbox.statuses) m.statuses.push_back(status(r));
  for (const core::StatusReport& r : progress) m.progress.push_back(status(r));
  return m;
}

core::MissionReport ToMissionReport(const Mission_Status& msg) {
  core::MissionReport r;
  r.mission_id = msg.mission_id;
  r.phase = static_cast<core::MissionPhase>(msg.state);
  r.reason = msg.reason;
  r.tick = msg.tick;
  r.robots_assigned = msg.robots_assigned;
  r.robots_inside = msg.robots_inside;
  r.distance_to_target_m = msg.distance_to_target;
  return r;
}

core::Perception ToPerception(std::uint16_t id, const Neighbors& msg) {
  core::Perception in;
  in.self_id = id;
  in.self = ToPose2(msg.pose);
  in.others.reserve(msg.robots.size() + msg.relayed.size() + msg.mission_peers.size());
  // In range, then passed on hop by hop (a chain's far end), then the mission channel.
  for (const auto* list : {&msg.robots, &msg.relayed, &msg.mission_peers}) {
    for (const Robot_Position& r : *list) {
      if (!IsFinite(r)) continue;
      in.others.push_back(ToNeighbour(r));
    }
  }
  return in;
}

core::Sender SenderOf(const std::string& node_name) {
  core::Sender sender;
  if (node_name == names::kDispatcherNode) {
    sender.kind = core::SenderKind::kDispatcher;
  } else if (node_name == names::kSimulatorNode ||
             node_name.rfind(names::kRobotHostNodePrefix, 0) == 0) {
    sender.kind = core::SenderKind::kRelay;
  } else {
    // "/robot_<id>/robot" with <id> in [0, 65535].
    const std::string prefix = "/robot_";  // names::RobotNamespace(id), at the root
    const std::string suffix = std::string("/") + names::kRobotNodeName;
    if (node_name.size() > prefix.size() + suffix.size() && node_name.rfind(prefix, 0) == 0 &&
        node_name.compare(node_name.size() - suffix.size(), suffix.size(), suffix) == 0) {
      const std::string digits =
          node_name.substr(prefix.size(), node_name.size() - prefix.size() - suffix.size());
      if (!digits.empty() && digits.size() <= 5 &&
          digits.find_first_not_of("0123456789") == std::string::npos &&
          std::stoul(digits) <= 65535) {
        sender.kind = core::SenderKind::kRobot;
        sender.robot_id = static_cast<std::uint16_t>(std::stoul(digits));
      }
    }
  }
  return sender;
}

core::FlockingTuning ToFlockingTuning(const Flocking_Tuning& msg) {
  core::FlockingTuning t;
  t.free_will_deg = msg.free_will_deg;
  t.cohesion = msg.cohesion;
  t.local_range_m = msg.local_range_m;
  t.speed_m_per_tick = msg.speed_m_per_tick;
  return t;
}

Flocking_Tuning ToTuningMsg(const core::FlockingTuning& tuning, std::uint32_t generation,
                            std::uint64_t tick) {
  Flocking_Tuning msg;
  msg.generation = generation;
  msg.tick = tick;
  msg.free_will_deg = tuning.free_will_deg;
  msg.cohesion = tuning.cohesion;
  msg.local_range_m = tuning.local_range_m;
  msg.speed_m_per_tick = tuning.speed_m_per_tick;
  return msg;
}

}  // namespace swarm_transport
