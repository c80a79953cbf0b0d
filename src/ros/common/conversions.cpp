#include "swarm_transport/ros/common/conversions.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <variant>

#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {

namespace {

Pose ToPoseMsg(const core::OwnPose& p) {
  Pose msg;
  msg.x = p.x;
  msg.y = p.y;
  msg.theta = p.theta;
  msg.linear_velocity = p.linear_velocity;
  msg.angular_velocity = p.angular_velocity;
  return msg;
}

core::OwnPose ToOwnPose(const Pose& msg) {
  return core::OwnPose{msg.x, msg.y, msg.theta, msg.linear_velocity, msg.angular_velocity};
}

std::vector<core::Position> ToPositions(const std::vector<Robot_Position>& list) {
  std::vector<core::Position> out;
  out.reserve(list.size());
  for (const Robot_Position& p : list) out.push_back(ToPosition(p));
  return out;
}

}  // namespace

core::Neighbour ToNeighbour(const Robot_Position& msg) {
  return core::NeighbourOf(ToPosition(msg));
}

Robot_Position ToRobotPosition(std::uint16_t id, const core::Pose2& pose, std::uint8_t sub_id,
                               std::uint8_t type) {
  return ToRobotPosition(core::PositionOf(id, pose, sub_id, type));
}

Robot_Position ToRobotPosition(const core::Position& p) {
  Robot_Position msg;
  msg.robot_id = p.robot_id;
  msg.sub_id = p.sub_id;
  msg.type = p.type;
  msg.pos_x = p.x;
  msg.pos_y = p.y;
  msg.angle = p.angle_deg;
  msg.copies = p.copies;
  return msg;
}

core::Position ToPosition(const Robot_Position& msg) {
  return core::Position{msg.robot_id, msg.sub_id, msg.type,  msg.pos_x,
                        msg.pos_y,    msg.angle,  msg.copies};
}

std::vector<Robot_Position> ToRobotPositions(const std::vector<core::Position>& positions) {
  std::vector<Robot_Position> out;
  out.reserve(positions.size());
  for (const core::Position& p : positions) out.push_back(ToRobotPosition(p));
  return out;
}

core::Pose2 ToPose2(const Pose& msg) { return core::Pose2Of(ToOwnPose(msg)); }

Pose ToPoseMsg(const core::Pose2& pose, const core::Velocity& velocity) {
  return ToPoseMsg(core::OwnPoseOf(pose, velocity));
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

New_Mission ToMsg(const core::MissionSpec& m) { return ToNewMission(m); }

Update_Object ToMsg(const core::ObjectUpdate& m) {
  Update_Object msg;
  msg.mission_id = m.mission_id;
  msg.object_position_x = static_cast<float>(m.centre.x);
  msg.object_position_y = static_cast<float>(m.centre.y);
  return msg;
}

Delete_Object ToMsg(const core::ObjectDelete& m) {
  Delete_Object msg;
  msg.mission_id = m.mission_id;
  return msg;
}

Robot_Freeze ToMsg(const core::Freeze& m) {
  Robot_Freeze msg;
  msg.robot_index_from = m.from;
  msg.robot_index_to = m.to;
  return msg;
}

Robot_Continue ToMsg(const core::Continue& m) {
  Robot_Continue msg;
  msg.robot_index_from = m.from;
  msg.robot_index_to = m.to;
  return msg;
}

Mission_Event ToMsg(const core::Signal& m) {
  Mission_Event msg;
  msg.mission_id = m.mission_id;
  msg.event = static_cast<std::uint8_t>(m.kind);
  msg.not_before_tick = m.not_before_tick;
  return msg;
}

Mission_Status ToMsg(const core::PhaseStatus& m) {
  Mission_Status msg;
  msg.mission_id = m.mission_id;
  msg.state = static_cast<std::uint8_t>(m.phase);
  msg.lost = m.lost;
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
  return core::PhaseStatus{msg.mission_id, static_cast<core::MissionPhase>(msg.state), msg.lost};
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

Neighbors ToNeighbors(const core::Round& round) {
  Neighbors msg;
  msg.tick = round.tick;
  msg.sim_time = round.sim_time;
  msg.pose = ToPoseMsg(round.pose);
  msg.robots = ToRobotPositions(round.robots);
  msg.relayed = ToRobotPositions(round.relayed);
  msg.mission_peers = ToRobotPositions(round.mission_peers);
  const auto add = [](const auto& m, auto* list) { list->push_back(ToMsg(m)); };
  for (const core::MissionMessage& m : round.messages) {
    std::visit(core::Overloaded{
                   [&](const core::MissionSpec& x) { add(x, &msg.missions); },
                   [&](const core::ObjectUpdate& x) { add(x, &msg.object_updates); },
                   [&](const core::ObjectDelete& x) { add(x, &msg.object_deletes); },
                   [&](const core::Freeze& x) { add(x, &msg.freezes); },
                   [&](const core::Continue& x) { add(x, &msg.continues); },
                   [&](const core::Signal& x) { add(x, &msg.mission_events); },
                   [&](const core::PhaseStatus& x) { add(x, &msg.statuses); },
               },
               m);
  }
  if (round.tuning) {
    msg.tuning.push_back(
        ToTuningMsg(round.tuning->tuning, round.tuning->generation, round.tuning->tick));
  }
  return msg;
}

core::Round ToRound(const Neighbors& msg) {
  core::Round round;
  round.tick = msg.tick;
  round.sim_time = msg.sim_time;
  round.pose = ToOwnPose(msg.pose);
  round.robots = ToPositions(msg.robots);
  round.relayed = ToPositions(msg.relayed);
  round.mission_peers = ToPositions(msg.mission_peers);
  round.messages = ToMissionMessages(msg);
  round.tuning = ToTuning(msg);
  return round;
}

std::optional<core::TuningGeneration> ToTuning(const Neighbors& msg) {
  if (msg.tuning.empty()) return std::nullopt;
  const Flocking_Tuning& t = msg.tuning.front();
  return core::TuningGeneration{t.generation, t.tick, ToFlockingTuning(t)};
}

Mission_Status ToStatusMsg(const core::StatusReport& r, std::uint64_t tick,
                           const ros::Time& stamp) {
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
  m.lost = r.lost;
  return m;
}

Tick_Answer ToTickAnswer(const core::Answer& answer, const ros::Time& stamp) {
  Tick_Answer msg;
  msg.tick = answer.tick;
  msg.command = ToTwist(answer.command);
  msg.copies = answer.copies;
  const auto add = [](const auto& m, auto* list) { list->push_back(ToMsg(m)); };
  for (const core::MissionMessage& m : answer.messages) {
    std::visit(core::Overloaded{
                   [&](const core::ObjectUpdate& x) { add(x, &msg.object_updates); },
                   [&](const core::ObjectDelete& x) { add(x, &msg.object_deletes); },
                   [&](const core::Freeze& x) { add(x, &msg.freezes); },
                   [&](const core::Continue& x) { add(x, &msg.continues); },
                   [](const auto&) {},  // no answer carries the others
               },
               m);
  }
  for (const core::StatusReport& r : answer.statuses) {
    msg.statuses.push_back(ToStatusMsg(r, answer.tick, stamp));
  }
  for (const core::StatusReport& r : answer.progress) {
    msg.progress.push_back(ToStatusMsg(r, answer.tick, stamp));
  }
  return msg;
}

core::Answer ToAnswer(const Tick_Answer& msg) {
  core::Answer answer;
  answer.tick = msg.tick;
  answer.copies = msg.copies;
  answer.command = IsFinite(msg.command)
                       ? ToVelocity(msg.command)
                       : core::Velocity{std::numeric_limits<double>::quiet_NaN(), 0.0};
  const auto add = [&answer](const auto& list) {
    for (const auto& m : list) answer.messages.push_back(ToMissionMessage(m));
  };
  add(msg.object_updates);
  add(msg.freezes);
  add(msg.continues);
  add(msg.object_deletes);
  for (const Mission_Status& s : msg.statuses) answer.statuses.push_back(ToStatusReport(s));
  for (const Mission_Status& s : msg.progress) answer.progress.push_back(ToStatusReport(s));
  if (!msg.statuses.empty()) {
    answer.sim_time = msg.statuses.front().stamp.toSec();
  } else if (!msg.progress.empty()) {
    answer.sim_time = msg.progress.front().stamp.toSec();
  }
  return answer;
}

core::StatusReport ToStatusReport(const Mission_Status& s) {
  core::StatusReport r;
  r.mission_id = s.mission_id;
  r.phase = static_cast<core::MissionPhase>(s.state);
  r.reason = s.reason;
  r.assigned = s.robots_assigned;
  r.inside = s.robots_inside;
  r.object = {s.object_position_x, s.object_position_y};
  r.distance_to_target = s.distance_to_target;
  r.lost = s.lost;
  return r;
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

Dispatcher_Answer ToMsg(const core::DispatcherAnswer& answer) {
  Dispatcher_Answer msg;
  msg.has_positions = answer.has_positions;
  msg.checked_tick = answer.checked_tick;
  if (answer.status) {
    msg.took_status = true;
    msg.status_mission_id = answer.status->mission_id;
    msg.status_state = static_cast<std::uint8_t>(answer.status->phase);
    msg.status_tick = answer.status->tick;
  }
  for (const auto& order : answer.orders) {
    msg.order_ids.push_back(order.first);
    msg.order_start_ticks.push_back(order.second);
  }
  for (const core::Signal& signal : answer.events) msg.events.push_back(ToMsg(signal));
  msg.hold_from_tick = answer.hold_from_tick;
  for (const core::RecruitStatist& r : answer.recruiting) {
    msg.recruiting.push_back(r.mission_id);
    msg.statists.push_back(StatistPosition(r.statist_id, r.at, 0));
    msg.statist_copies.push_back(static_cast<std::uint8_t>(r.copies));
    msg.statist_from_ticks.push_back(r.from_tick);
  }
  return msg;
}

core::DispatcherAnswer ToDispatcherAnswer(const Dispatcher_Answer& msg) {
  core::DispatcherAnswer answer;
  answer.has_positions = msg.has_positions;
  answer.checked_tick = msg.checked_tick;
  if (msg.took_status) {
    answer.status = core::StatusKey{
        msg.status_mission_id, static_cast<core::MissionPhase>(msg.status_state), msg.status_tick};
  }
  const std::size_t n = std::min(msg.order_ids.size(), msg.order_start_ticks.size());
  for (std::size_t i = 0; i < n; ++i) {
    answer.orders.emplace_back(msg.order_ids[i], msg.order_start_ticks[i]);
  }
  for (const Mission_Event& e : msg.events) {
    answer.events.push_back(std::get<core::Signal>(ToMissionMessage(e)));
  }
  answer.hold_from_tick = msg.hold_from_tick;
  const std::size_t r = std::min({msg.recruiting.size(), msg.statists.size(),
                                  msg.statist_copies.size(), msg.statist_from_ticks.size()});
  for (std::size_t i = 0; i < r; ++i) {
    const Robot_Position& s = msg.statists[i];
    answer.recruiting.push_back({msg.recruiting[i],
                                 s.robot_id,
                                 {s.pos_x, s.pos_y},
                                 msg.statist_copies[i],
                                 msg.statist_from_ticks[i]});
  }
  return answer;
}

Robot_Position StatistPosition(std::uint16_t statist_id, core::Vec2 at, std::uint8_t sub_id) {
  Robot_Position statist;
  statist.robot_id = statist_id;
  statist.sub_id = sub_id;
  statist.type = Robot_Position::TYPE_STATIST;
  statist.pos_x = static_cast<float>(at.x);
  statist.pos_y = static_cast<float>(at.y);
  return statist;
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
