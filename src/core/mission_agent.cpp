#include "swarm_transport/core/mission_agent.h"

#include <algorithm>
#include <sstream>

namespace swarm_transport {
namespace core {

MissionAgent::MissionAgent(std::uint16_t self_id, const MissionAgentParams& params)
    : self_id_(self_id), params_(params) {}

bool MissionAgent::OnNewMission(const MissionSpec& mission, std::string* why) {
  if (live_.count(mission.id) > 0) {
    *why = "mission_id " + std::to_string(mission.id) + " is already live";
    return false;
  }
  Live live;
  live.spec = mission;
  live.centre = mission.object_centre;
  live_.emplace(mission.id, live);
  if (mission.Assigns(self_id_)) queue_.push_back(mission.id);
  return true;
}

bool MissionAgent::OnObjectUpdate(std::uint16_t mission_id, Vec2 centre, std::string* why) {
  auto it = live_.find(mission_id);
  if (it == live_.end()) {
    *why = "Update_Object for unknown mission " + std::to_string(mission_id);
    return false;
  }
  it->second.centre = centre;
  return true;
}

bool MissionAgent::OnObjectDelete(std::uint16_t mission_id, std::string* why) {
  if (live_.count(mission_id) == 0) {
    *why = "Delete_Object for unknown mission " + std::to_string(mission_id);
    return false;
  }
  Drop(mission_id);
  return true;
}

bool MissionAgent::OnEvent(std::uint16_t mission_id, MissionEventKind event,
                           std::uint64_t not_before_tick, std::string* why) {
  auto it = live_.find(mission_id);
  if (it == live_.end()) {
    *why = "Mission_Event for unknown mission " + std::to_string(mission_id);
    return false;
  }
  Live& live = it->second;
  if (live.spec.FirstLeader() != self_id_) return true;  // only the first leader acts on it
  const MissionPhase expected =
      event == MissionEventKind::kLoaded ? MissionPhase::kLoading : MissionPhase::kUnloading;
  if (live.phase != expected) {
    *why = std::string("Mission_Event ") +
           (event == MissionEventKind::kLoaded ? "LOADED" : "UNLOADED") + " for mission " +
           std::to_string(mission_id) + " in phase " + PhaseName(live.phase) + " (expected " +
           PhaseName(expected) + ")";
    return false;
  }
  if (event == MissionEventKind::kLoaded) {
    live.loaded = true;
  } else {
    live.unloaded = true;
  }
  live.signal_tick = not_before_tick;
  return true;
}

void MissionAgent::OnStatus(std::uint16_t mission_id, MissionPhase phase) {
  auto it = live_.find(mission_id);
  if (it == live_.end() || it->second.spec.FirstLeader() == self_id_) return;
  // QUEUED and REJECTED come from the dispatcher (a REJECTED may name a live mission's id when
  // a duplicate was refused): only the first leader's phases move a mission on.
  if (phase == MissionPhase::kQueued || phase == MissionPhase::kRejected) return;
  // Phases only move forward; a late or repeated report must not turn the clock back.
  if (static_cast<int>(phase) > static_cast<int>(it->second.phase)) it->second.phase = phase;
}

std::set<std::uint16_t> MissionAgent::LiveIds() const {
  std::set<std::uint16_t> ids;
  for (const auto& kv : live_) ids.insert(kv.first);
  return ids;
}

MissionPhase MissionAgent::PhaseOf(std::uint16_t mission_id) const {
  auto it = live_.find(mission_id);
  return it == live_.end() ? MissionPhase::kDone : it->second.phase;
}

bool MissionAgent::IsFirstLeaderOfAny() const {
  return std::any_of(live_.begin(), live_.end(), [this](const auto& kv) {
    return kv.second.spec.FirstLeader() == self_id_;
  });
}

void MissionAgent::Drop(std::uint16_t mission_id) {
  live_.erase(mission_id);
  queue_.erase(std::remove(queue_.begin(), queue_.end(), mission_id), queue_.end());
}

StatusReport MissionAgent::Report(const Live& live, std::uint16_t inside) const {
  StatusReport r;
  r.mission_id = live.spec.id;
  r.phase = live.phase;
  r.assigned = static_cast<std::uint16_t>(live.spec.Assigned().size());
  r.inside = inside;
  r.object = live.centre;
  r.distance_to_target = Distance(live.centre, live.spec.target);
  return r;
}

void MissionAgent::EnterPhase(Live* live, MissionPhase phase, std::uint64_t tick,
                              std::uint16_t inside, MissionOutbox* outbox) {
  live->phase = phase;
  live->phase_tick = tick;
  outbox->statuses.push_back(Report(*live, inside));
}

std::vector<std::pair<std::uint16_t, std::uint16_t>> MissionAgent::OthersRuns(
    const MissionSpec& spec) const {
  std::vector<std::pair<std::uint16_t, std::uint16_t>> runs;
  for (const auto& run : spec.AssignedRuns()) {
    if (self_id_ < run.first || self_id_ >= run.second) {
      runs.push_back(run);
      continue;
    }
    if (run.first < self_id_) runs.emplace_back(run.first, self_id_);
    if (self_id_ + 1 < run.second) runs.emplace_back(static_cast<std::uint16_t>(self_id_ + 1), run.second);
  }
  return runs;
}

void MissionAgent::UpdateDocking(Live* live, double to_target, std::uint64_t tick,
                                 MissionOutbox* outbox) {
  // The swarm brings the object near the target fast, but its passive robots cannot stop on a
  // 5 cm tolerance: their alignment carries the centroid past it, back and forth for hundreds
  // of ticks. So the last few centimetres are the first leader's alone.
  if (params_.docking_radius_m <= 0.0) return;
  if (!live->docking) {
    if (to_target <= params_.docking_radius_m && tick >= live->docking_retry_tick) {
      live->docking = true;
      live->docking_best_m = to_target;
      live->docking_best_tick = tick;
      outbox->freeze = OthersRuns(live->spec);
    }
    return;
  }
  if (to_target < live->docking_best_m - 1e-6) {
    live->docking_best_m = to_target;
    live->docking_best_tick = tick;
  } else if (tick - live->docking_best_tick > params_.docking_patience_ticks) {
    // Blocked (a frozen robot in its way): let the swarm move again and retry later.
    live->docking = false;
    live->docking_retry_tick = tick + params_.docking_patience_ticks;
    outbox->resume = OthersRuns(live->spec);
  }
}

void MissionAgent::RunFirstLeader(Live* live, const Pose2& self,
                                  const std::vector<Neighbour>& heard, std::uint64_t tick,
                                  MissionOutbox* outbox) {
  const MissionSpec& spec = live->spec;
  if (!live->phase_started) {
    live->phase_started = true;
    EnterPhase(live, spec.LeaderOnly() ? MissionPhase::kTransport : MissionPhase::kGathering,
               tick, 0, outbox);
  }
  if (spec.LeaderOnly()) return;  // ends in LeaderArrived

  // Where every assigned robot is: itself, and what the radio brought (range or mission peers).
  std::map<std::uint16_t, Vec2> where;
  where[self_id_] = self.position;
  for (const Neighbour& n : heard) {
    if (n.type == 0 && spec.Assigns(n.id)) where.emplace(n.id, n.position);
  }
  const std::vector<std::uint16_t> assigned = spec.Assigned();
  const Shape object = spec.ObjectAt(live->centre);
  std::uint16_t inside = 0;
  Vec2 sum;
  for (const auto& kv : where) {
    if (object.Contains(kv.second)) ++inside;
    sum = sum + kv.second;
  }
  const Vec2 centroid = sum * (1.0 / static_cast<double>(where.size()));
  const bool periodic = params_.progress_every_ticks > 0 &&
                        (tick - live->phase_tick) % params_.progress_every_ticks == 0 &&
                        tick != live->phase_tick;

  if (tick - live->phase_tick > params_.phase_timeout_ticks &&
      live->phase != MissionPhase::kDone) {
    std::ostringstream why;
    why << "phase " << PhaseName(live->phase) << " lasted more than "
        << params_.phase_timeout_ticks << " ticks";
    outbox->resume = spec.AssignedRuns();
    outbox->delete_object = spec.id;
    EnterPhase(live, MissionPhase::kAborted, tick, inside, outbox);
    outbox->statuses.back().reason = why.str();
    return;
  }

  switch (live->phase) {
    case MissionPhase::kGathering:
      if (inside == assigned.size()) {
        outbox->freeze = spec.AssignedRuns();
        EnterPhase(live, MissionPhase::kLoading, tick, inside, outbox);
      } else if (periodic) {
        outbox->statuses.push_back(Report(*live, inside));
      }
      break;
    case MissionPhase::kLoading:
      if (live->loaded && tick >= live->signal_tick) {
        outbox->resume = spec.AssignedRuns();
        live->offset = live->centre - centroid;
        live->transport_ticks = 0;
        EnterPhase(live, MissionPhase::kTransport, tick, inside, outbox);
      }
      break;
    case MissionPhase::kTransport: {
      live->centre = live->offset + centroid;
      ++live->transport_ticks;
      const double to_target = Distance(live->centre, spec.target);
      if (to_target <= params_.goal_tolerance_m) {
        live->docking = false;
        outbox->update_object = std::make_pair(spec.id, live->centre);
        outbox->freeze = spec.AssignedRuns();
        EnterPhase(live, MissionPhase::kUnloading, tick, inside, outbox);
      } else {
        UpdateDocking(live, to_target, tick, outbox);
        if (live->transport_ticks % static_cast<std::uint64_t>(params_.object_update_ticks) == 0) {
          outbox->update_object = std::make_pair(spec.id, live->centre);
        }
        if (periodic) outbox->statuses.push_back(Report(*live, inside));
      }
      break;
    }
    case MissionPhase::kUnloading:
      if (live->unloaded && tick >= live->signal_tick) {
        outbox->resume = spec.AssignedRuns();
        outbox->delete_object = spec.id;
        EnterPhase(live, MissionPhase::kDone, tick, inside, outbox);
      }
      break;
    default:
      break;
  }
}

MissionPlan MissionAgent::Tick(const Pose2& self, const std::vector<Neighbour>& heard,
                               std::uint64_t tick, MissionOutbox* outbox) {
  MissionPlan plan;
  if (!queue_.empty()) plan.active = queue_.front();
  if (plan.active) {
    Live& live = live_.at(*plan.active);
    if (outbox != nullptr && live.spec.FirstLeader() == self_id_) {
      RunFirstLeader(&live, self, heard, tick, outbox);
    }
  }
  if (plan.active) {
    const Live& live = live_.at(*plan.active);
    const MissionSpec& spec = live.spec;
    if (spec.IsLeader(self_id_) && !live.self_arrived) {
      if (spec.LeaderOnly()) {
        plan.lead = true;
        plan.keep_flock = true;
        plan.goal = spec.target;
        plan.steer = Bearing(self.position, spec.target);
      } else if (live.phase == MissionPhase::kTransport) {
        // Steer along object centre -> target, so leaders do not circle the target [T5.4].
        plan.lead = true;
        plan.keep_flock = false;
        plan.steer = Bearing(live.centre, spec.target);
        plan.goal = spec.target + (self.position - live.centre);
        if (live.docking) {
          // The others stand: moving d moves the object d / n, so it aims n times as far (a
          // leader drives at most its speed and never farther than its goal).
          const double n = static_cast<double>(spec.Assigned().size());
          plan.goal = self.position + (spec.target - live.centre) * n;
        }
      }
    }
  }
  for (const auto& kv : live_) {
    const Live& live = kv.second;
    if (live.spec.LeaderOnly()) continue;  // a leader-only mission has no object
    const bool active = plan.active && *plan.active == kv.first;
    // A leader carrying its object is not kept inside it: the object rides on the robots and
    // follows their centroid, so a leader held at its border would hold the object too. It
    // heads for the target, slows or waits only for robots in its way (the thesis counts a
    // leader wait only "when another robot blocked its way" [T7.4]); the passive robots flee
    // into the object as it moves. Once arrived it is passive and the object is safety again.
    if (active && plan.lead) continue;
    Zone zone;
    zone.id = live.spec.id;
    zone.shape = live.spec.ObjectAt(live.centre);
    // Its own active object is safety (all else is danger); any other object is danger.
    zone.inverted = active;
    plan.zones.push_back(zone);
  }
  return plan;
}

void MissionAgent::LeaderArrived(std::uint16_t mission_id, MissionOutbox* outbox) {
  auto it = live_.find(mission_id);
  if (it == live_.end() || !it->second.spec.LeaderOnly()) return;
  Live& live = it->second;
  live.self_arrived = true;
  if (live.spec.FirstLeader() == self_id_ && live.phase != MissionPhase::kDone) {
    outbox->delete_object = mission_id;
    EnterPhase(&live, MissionPhase::kDone, live.phase_tick, 0, outbox);
  }
}

}  // namespace core
}  // namespace swarm_transport
