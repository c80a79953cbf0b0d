#include "swarm_transport/core/robot_brain.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>
#include <variant>

namespace swarm_transport {
namespace core {
namespace {

MissionAgentParams MissionParams(const SwarmConfig& p) {
  MissionAgentParams m;
  m.goal_tolerance_m = p.leader.goal_tolerance_m;
  m.object_update_ticks = p.object_update_ticks;
  m.transport = p.transport;
  m.local_range_m = p.flocking.local_range_m;
  m.world_size_m = p.flocking.world_size_m;
  m.speed_m_per_tick = p.flocking.speed_m_per_tick;
  m.static_zones = p.danger_zones;
  m.corridor_m = p.flocking.MinSeparation();
  m.min_robots = p.mission_min_robots;
  m.loading_spread = p.loading_spread;
  m.loading_spread_ticks = p.loading_spread_ticks;
  m.lost_after_ticks =
      static_cast<std::uint64_t>(std::max(1.0, std::ceil(p.lost_after_s / p.tick_period_s - 1e-9)));
  return m;
}

std::string BadRange(const char* what, std::uint16_t from, std::uint16_t to) {
  std::ostringstream os;
  os << what << " [" << from << ", " << to << "): the range is empty or inverted";
  return os.str();
}

}  // namespace

RobotBrain::RobotBrain(std::uint16_t id, const SwarmConfig& config)
    : id_(id),
      params_(config),
      rng_(config.seed, id),
      agent_(id, MissionParams(config)),
      balloon_radius_m_(config.flocking.robot_radius_m) {}

std::string RobotBrain::Take(const MissionMessage& message,
                             const std::set<std::uint16_t>& known_robots, MissionTaken* taken) {
  return std::visit(
      [&](const auto& m) -> std::string {
        using M = std::decay_t<decltype(m)>;
        if constexpr (std::is_same_v<M, MissionSpec>) {
          return OnNewMission(m, known_robots, taken);
        } else if constexpr (std::is_same_v<M, ObjectUpdate>) {
          return OnObjectUpdate(m.mission_id, m.centre);
        } else if constexpr (std::is_same_v<M, ObjectDelete>) {
          return OnObjectDelete(m.mission_id);
        } else if constexpr (std::is_same_v<M, Freeze>) {
          return OnFreeze(m.from, m.to);
        } else if constexpr (std::is_same_v<M, Continue>) {
          return OnContinue(m.from, m.to);
        } else if constexpr (std::is_same_v<M, Signal>) {
          return OnEvent(m.mission_id, m.kind, m.not_before_tick);
        } else {
          static_assert(std::is_same_v<M, PhaseStatus>, "a mission message without its case");
          OnStatus(m);
          return "";
        }
      },
      message);
}

std::string RobotBrain::OnFreeze(std::uint16_t from, std::uint16_t to) {
  if (from >= to) return BadRange("freeze", from, to);
  if (InRange(from, to)) frozen_ = true;
  return "";
}

std::string RobotBrain::OnContinue(std::uint16_t from, std::uint16_t to) {
  if (from >= to) return BadRange("continue", from, to);
  if (InRange(from, to)) frozen_ = false;
  return "";
}

std::string RobotBrain::OnNewMission(const MissionSpec& mission,
                                     const std::set<std::uint16_t>& known_robots,
                                     MissionTaken* taken) {
  MissionContext context;
  context.world_size_m = params_.flocking.world_size_m;
  context.known_robots_view = &known_robots;  // not copied: every robot checks every order
  context.live_missions = agent_.LiveIds();
  context.static_zones = params_.danger_zones;
  // Admitted by the dispatcher already, or admitted here with the dispatcher's own decision.
  if (params_.admission == Admission::kRobots)
    context.max_live_missions = params_.max_live_missions;
  std::string why = AdmitMission(mission, context);
  if (!why.empty() || !agent_.OnNewMission(mission, &why)) return why;
  if (taken != nullptr) {
    *taken = MissionTaken();
    taken->first_leader = mission.FirstLeader() == id_;
    // The mission's first status: its first leader holds the order and queues it [T6.4].
    StatusReport& queued = taken->queued;
    queued.mission_id = mission.id;
    queued.phase = MissionPhase::kQueued;
    queued.assigned =
        static_cast<std::uint16_t>(std::min<std::size_t>(mission.Assigned().size(), 65535));
    queued.object = mission.object_centre;
    queued.distance_to_target = Distance(mission.object_centre, mission.target);
  }
  return "";
}

std::string RobotBrain::OnObjectUpdate(std::uint16_t mission_id, Vec2 centre) {
  if (!std::isfinite(centre.x) || !std::isfinite(centre.y)) {
    std::ostringstream os;
    os << "object update " << mission_id << ": non-finite position";
    return os.str();
  }
  std::string why;
  return agent_.OnObjectUpdate(mission_id, centre, &why) ? "" : why;
}

std::string RobotBrain::OnObjectDelete(std::uint16_t mission_id) {
  const MissionSpec* spec = agent_.Find(mission_id);
  const bool member = spec != nullptr && spec->Assigns(id_);
  std::string why;
  if (!agent_.OnObjectDelete(mission_id, &why)) return why;
  // The object is gone: nothing holds its robots any more (an object delete before the first
  // leader's Continue, or instead of it, left them frozen for good; issue 11).
  if (member) frozen_ = false;
  return "";
}

std::string RobotBrain::OnEvent(std::uint16_t mission_id, MissionEventKind event,
                                std::uint64_t not_before_tick) {
  if (event != MissionEventKind::kLoaded && event != MissionEventKind::kUnloaded) {
    std::ostringstream os;
    os << "signal " << mission_id << ": event must be 1 (LOADED) or 2 (UNLOADED)";
    return os.str();
  }
  std::string why;
  return agent_.OnEvent(mission_id, event, not_before_tick, &why) ? "" : why;
}

void RobotBrain::OnStatus(const PhaseStatus& status) {
  if (status.phase <= MissionPhase::kRejected) {
    agent_.OnStatus(status.mission_id, status.phase, status.lost);
  }
}

std::string RobotBrain::OnTuning(const FlockingTuning& tuning) {
  const std::string why = params_.Retune(tuning);
  if (!why.empty()) return "flocking tuning: " + why;
  agent_.Retune(params_.flocking.local_range_m, params_.flocking.speed_m_per_tick);
  return "";
}

BrainTick RobotBrain::Tick(Perception in, std::uint64_t tick, bool publish) {
  BrainTick out;
  in.self_id = id_;
  // The plan lives in last_plan_ (moved there, not copied: a tick's lists are its own).
  last_plan_ = agent_.Tick(in.self, in.others, tick, publish ? &out.outbox : nullptr);
  const MissionPlan& plan = last_plan_;
  in.zones = params_.danger_zones;
  in.zones.insert(in.zones.end(), plan.zones.begin(), plan.zones.end());
  in.group = plan.group;

  const double dt = params_.tick_period_s;
  // A robot that hears a leader's virtual copies (SPEC 9.2) flocks to follow it rather than
  // spread out.
  const bool balloon = params_.standby == StandbyMode::kBalloon && !plan.active && !plan.carry &&
                       !plan.lead &&
                       std::none_of(in.others.begin(), in.others.end(),
                                    [](const Neighbour& n) { return n.copies > 0; });
  // Loading spread (SPEC 9.5): until the first leader's freeze, a mission robot in LOADING
  // spreads under its object.
  const bool spreading = params_.loading_spread == LoadingSpread::kBalloon && plan.carry &&
                         plan.carry->loading && !frozen_;
  // A balloon grows anew each time its robot returns to standby (or starts to spread).
  if (!balloon && !spreading) balloon_radius_m_ = params_.flocking.robot_radius_m;
  if (spreading) {
    const Carry& carry = *plan.carry;
    const Vec2 size =
        carry.object.parts().empty() ? Vec2{} : carry.object.parts().front().rect.size;
    out.move =
        LoadingBalloonStep(in, params_.flocking, params_.balloon, Rect{carry.centre, size},
                           carry.peers, carry.leader && params_.transport.leaders_face_course,
                           Bearing(carry.centre, carry.target), rng_, dt, &balloon_radius_m_);
  } else if (plan.carry) {
    out.move = CarryStep(in, params_.flocking, params_.transport, *plan.carry, rng_, dt);
  } else if (plan.lead) {
    if (leader_memory_mission_ != plan.active) {
      leader_memory_ = LeaderMemory();
      leader_memory_mission_ = plan.active;
    }
    LeaderParams leader = params_.leader;
    leader.keep_flock = leader.keep_flock && plan.keep_flock;
    const LeaderDecision d =
        LeaderStep(in, params_.flocking, leader, plan.goal, plan.steer, rng_, dt, &leader_memory_);
    out.move = d.move;
    // Virtual leaders (SPEC 9.2): it announces its copies; its hearers count each one as a
    // neighbour (collisions see only the robots).
    out.copies = static_cast<std::uint8_t>(params_.leader.virtual_copies - 1);
    if (d.arrived) {
      agent_.LeaderArrived(*plan.active, &out.outbox);
      out.arrived = true;
    }
  } else if (balloon) {
    // Balloon dispersion (SPEC 9.5): on no mission, it spreads over the arena.
    out.move = BalloonStep(in, params_.flocking, params_.balloon, rng_, dt, &balloon_radius_m_);
  } else {
    out.move = FlockingStep(in, params_.flocking, rng_, dt);
  }
  last_move_ = out.move;
  last_heard_ = in.others.size();
  last_self_ = in.self;
  // A frozen robot keeps computing (its random sequence stays aligned) but does not drive; a
  // leader under its object may still turn in place to face its course.
  if (!frozen_) {
    out.command = CommandFor(in.self, out.move.heading, out.move.distance_m, dt);
  } else if (plan.carry && plan.carry->leader && out.move.distance_m == 0.0) {
    out.command = CommandFor(in.self, out.move.heading, 0.0, dt);
  }
  return out;
}

}  // namespace core
}  // namespace swarm_transport
