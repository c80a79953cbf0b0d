#include "swarm_transport/ros/robot/robot_report.h"

#include <sstream>

namespace swarm_transport {

Robot_State::Response StateOf(const core::RobotSession& session, std::uint64_t ticks, bool listed) {
  const core::RobotBrain& brain = session.brain();
  const core::MissionPlan& plan = brain.last_plan();
  const core::MoveDecision& move = brain.last_move();
  Robot_State::Response state;
  state.robot_id = session.id();
  state.ticks = ticks;
  state.listed = listed;
  state.round_age_s = -1.0;  // the node knows these (RobotNode::State)
  state.command_listeners = -1;
  state.frozen = brain.frozen();
  state.leader = plan.lead || (plan.carry && plan.carry->leader);  // alone or of a transport
  state.has_active = plan.active.has_value();
  state.active_mission = plan.active.value_or(0);
  for (std::uint16_t m : brain.missions().LiveIds()) {
    state.mission_ids.push_back(m);
    state.mission_phases.push_back(static_cast<std::uint8_t>(brain.missions().PhaseOf(m)));
  }
  for (const core::Zone& z : plan.zones) {
    state.zone_ids.push_back(z.id);
    state.zone_safety.push_back(z.inverted);
  }
  state.heard = static_cast<std::uint32_t>(brain.last_heard());
  state.desired_heading_deg = move.desired_heading.degrees();
  state.heading_deg = move.heading.degrees();
  state.distance_m = move.distance_m;
  state.fleeing = move.fleeing;
  const core::Pose2& self = brain.last_self();
  state.x = self.position.x;
  state.y = self.position.y;
  state.theta_deg = self.heading.degrees();
  if (plan.carry) {
    state.carrying = true;
    state.object_x = plan.carry->centre.x;
    state.object_y = plan.carry->centre.y;
    state.target_x = plan.carry->target.x;
    state.target_y = plan.carry->target.y;
    state.inside = plan.carry->object.Contains(self.position);
  }
  state.tuning_generation = session.tuning_generation();
  state.tuning_tick = session.tuning_tick();
  const core::FlockingTuning tuning = brain.tuning();
  state.free_will_deg = tuning.free_will_deg;
  state.cohesion = tuning.cohesion;
  state.local_range_m = tuning.local_range_m;
  state.speed_m_per_tick = tuning.speed_m_per_tick;
  return state;
}

std::string Describe(const Robot_State::Response& s) {
  std::ostringstream os;
  os << "id=" << s.robot_id << " ticks=" << s.ticks << " frozen=" << (s.frozen ? 1 : 0)
     << " role=" << (s.leader ? "leader" : "passive") << " active=";
  if (s.has_active) {
    os << s.active_mission;
  } else {
    os << "none";
  }
  os << " missions=[";
  for (std::size_t i = 0; i < s.mission_ids.size(); ++i) {
    os << s.mission_ids[i] << ":"
       << core::PhaseName(static_cast<core::MissionPhase>(s.mission_phases[i])) << " ";
  }
  os << "] zones=[";
  for (std::size_t i = 0; i < s.zone_ids.size(); ++i) {
    os << s.zone_ids[i] << (s.zone_safety[i] ? ":safety " : ":danger ");
  }
  os << "] heard=" << s.heard << " desired=" << s.desired_heading_deg
     << " heading=" << s.heading_deg << " distance=" << s.distance_m
     << " fleeing=" << (s.fleeing ? 1 : 0) << " at=(" << s.x << ", " << s.y << ", " << s.theta_deg
     << ")";
  if (s.carrying) {
    os << " object=(" << s.object_x << ", " << s.object_y << ")->(" << s.target_x << ", "
       << s.target_y << ") inside=" << (s.inside ? 1 : 0);
  }
  if (s.round_age_s >= 0.0) {
    os << " round_age=" << s.round_age_s << " round_waits=" << s.round_waits
       << " late_cmd_rounds=" << s.late_command_rounds;
  }
  if (s.command_listeners >= 0) os << " cmd_listeners=" << s.command_listeners;
  os << " free_will=" << s.free_will_deg << " cohesion=" << s.cohesion
     << " range=" << s.local_range_m << " speed=" << s.speed_m_per_tick
     << " tuning=" << s.tuning_generation;
  return os.str();
}

void FillStatus(const Robot_State::Response& st, std::uint64_t tick, NodeStatus* s) {
  if (!st.listed) {
    s->level = diagnostic_msgs::DiagnosticStatus::WARN;
    s->message = "not in the swarm: idle until spawned";
  } else {
    s->message = "tick " + std::to_string(tick);
    if (st.frozen) s->message += ", frozen";
    if (st.has_active) {
      s->message +=
          ", mission " + std::to_string(st.active_mission) + (st.leader ? " (leader)" : "");
    }
  }
  s->Add("ticks", st.ticks);
  s->Add("listed", st.listed ? "true" : "false");
  s->Add("frozen", st.frozen ? "true" : "false");
  s->Add("missions", static_cast<std::uint64_t>(st.mission_ids.size()));
  s->Add("heard", static_cast<std::uint64_t>(st.heard));
}

}  // namespace swarm_transport
