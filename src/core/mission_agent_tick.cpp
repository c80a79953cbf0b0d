#include <algorithm>
#include <map>
#include <sstream>
#include <utility>

#include "swarm_transport/core/assignment.h"
#include "swarm_transport/core/mission_agent.h"

// A mission's tick as its members run it: where the group stands, where the object is and the
// first leader's phases (the book-keeping of the messages: mission_agent.cpp; each member's slot
// and way while gathering: mission_agent_gather.cpp).

namespace swarm_transport {
namespace core {
namespace {
// Two views of a transport's object closer than this are the same object (updates are sent
// as float32: ~5e-7 m apart at 11 m).
constexpr double kSameObjectM = 1e-5;
}  // namespace

bool MissionAgent::Group::OneChain(double range) const {
  std::vector<Vec2> left;
  for (const auto& kv : where) left.push_back(kv.second);
  if (left.empty()) return true;
  std::vector<Vec2> linked{left.back()};
  left.pop_back();
  for (std::size_t next = 0; next < linked.size() && !left.empty(); ++next) {
    const Vec2 from = linked[next];
    auto far = std::partition(left.begin(), left.end(),
                              [&](const Vec2& p) { return Distance(from, p) > range; });
    linked.insert(linked.end(), far, left.end());
    left.erase(far, left.end());
  }
  return left.empty();
}

MissionAgent::Group MissionAgent::Locate(const Live& live, const Pose2& self,
                                         const std::vector<Neighbour>& heard) const {
  const MissionSpec& spec = live.spec;
  Group group;
  group.where[self_id_] = self.position;
  for (const Neighbour& n : heard) {
    if (n.type == 0 && spec.Assigns(n.id) && live.lost.count(n.id) == 0) {
      group.where.emplace(n.id, n.position);
    }
  }
  // A member not heard now but not lost yet stands where it was last heard.
  for (const auto& kv : live.last_seen) group.where.emplace(kv.first, kv.second);
  Vec2 sum;
  for (const auto& kv : group.where) sum = sum + kv.second;
  group.centroid = sum * (1.0 / static_cast<double>(group.where.size()));
  return group;
}

void MissionAgent::UpdateCentre(Live* live, const Pose2& self, Group* group) const {
  // Transport began (this robot learns it from the first leader's status, the first leader
  // itself when it enters the phase): everyone was frozen since LOADING, so every robot anchors
  // the object to the same centroid, and from then on moves it with the robots' centroid.
  if (live->phase >= MissionPhase::kTransport && live->phase <= MissionPhase::kUnloading) {
    if (!live->anchored) {
      live->anchored = true;
      live->offset = params_.transport.object_at_centroid ? Vec2{} : live->centre - group->centroid;
      live->centre = live->offset + group->centroid;
      live->place = self.position - live->centre;
    } else if (live->reanchor) {
      // A member was lost: the object stays where it is and moves with the robots left.
      live->offset = live->centre - group->centroid;
    }
    if (live->leader_centre && live->last_centroid) {
      // The first leader's object (of its tick before this one) is the mission's. A robot whose
      // own drifted from it takes it, as of its own centroid then: one that anchored late (its
      // TRANSPORT came after the others moved off) or heard other robots than the first leader
      // carried an object of its own, chased it from outside and led the others astray (a
      // soak's transport wandered for minutes without getting nearer its target). In lock-step
      // every robot's view is the first leader's and nothing changes.
      const Vec2 own = live->offset + *live->last_centroid;
      if (Distance(own, *live->leader_centre) > kSameObjectM) {
        live->offset = *live->leader_centre - *live->last_centroid;
      }
    }
    live->leader_centre.reset();
    live->reanchor = false;
    live->centre = live->offset + group->centroid;
    live->last_centroid = group->centroid;
    // The arena's walls hold the object: robots that drive on along a wall leave it behind (it
    // slips from them, its offset to them changes) instead of carrying it through. Robots outside
    // an object held beyond the wall would chase its centre into the wall for good (a soak's
    // mission stood in TRANSPORT at x 11.37 in the 11.09 m arena until its phase timed out).
    const Vec2 held = InsideArena(live->centre, live->spec.object_size, params_.world_size_m);
    if (held.x != live->centre.x || held.y != live->centre.y) {
      live->offset = held - group->centroid;
      live->centre = held;
    }
  }
  const Shape object = live->spec.ObjectAt(live->centre);
  group->inside = 0;
  for (const auto& kv : group->where) {
    if (object.Contains(kv.second)) ++group->inside;
  }
}

void MissionAgent::RunFirstLeader(Live* live, const Pose2& self, const Group& group,
                                  std::uint64_t tick, MissionOutbox* outbox) {
  const MissionSpec& spec = live->spec;
  const std::uint16_t inside = group.inside;
  std::ostringstream lost;
  for (std::uint16_t id : live->lost) lost << (lost.tellp() > 0 ? ", " : "") << id;
  const std::string lost_for =
      " lost (not heard for " + std::to_string(params_.lost_after_ticks) + " ticks)";
  if (!live->phase_started) {
    live->phase_started = true;
    if (live->phase == MissionPhase::kQueued) {
      EnterPhase(live, spec.LeaderOnly() ? MissionPhase::kTransport : MissionPhase::kGathering,
                 tick, 0, outbox);
    } else {
      // Promoted into a running phase: it says so (the phase again, with the reason).
      live->phase_tick = tick;
      outbox->statuses.push_back(Report(*live, inside));
    }
    if (live->promoted) {
      outbox->statuses.back().reason =
          "robot " + std::to_string(self_id_) + " leads: robot(s) " + lost.str() + lost_for;
      live->lost_told = live->lost.size();
    }
  }
  // A report within the phase every progress_every_ticks, in every phase: also the first
  // leader's heartbeat (the dispatcher ends a mission whose first leader fell silent).
  const bool periodic = params_.progress_every_ticks > 0 &&
                        (tick - live->phase_tick) % params_.progress_every_ticks == 0 &&
                        tick != live->phase_tick;
  if (spec.LeaderOnly()) {  // ends in LeaderArrived
    if (periodic && live->phase == MissionPhase::kTransport) {
      outbox->statuses.push_back(Report(*live, inside));
    }
    return;
  }

  if (tick - live->phase_tick > params_.phase_timeout_ticks && live->phase != MissionPhase::kDone) {
    std::ostringstream why;
    why << "phase " << PhaseName(live->phase) << " lasted more than " << params_.phase_timeout_ticks
        << " ticks";
    outbox->resume = spec.AssignedRuns();
    outbox->delete_object = spec.id;
    EnterPhase(live, MissionPhase::kAborted, tick, inside, outbox);
    outbox->statuses.back().reason = why.str();
    return;
  }

  // Lost members are dropped: the rest goes on without them, unless too few are left to staff
  // the leaders (or fewer than min_robots).
  const std::size_t left = Left(*live).size();
  const std::size_t needed =
      static_cast<std::size_t>(std::max(spec.leader_number, params_.min_robots));
  if (!live->lost.empty() && left < needed && live->phase >= MissionPhase::kGathering &&
      live->phase <= MissionPhase::kUnloading) {
    outbox->resume = spec.AssignedRuns();
    outbox->delete_object = spec.id;
    EnterPhase(live, MissionPhase::kAborted, tick, inside, outbox);
    outbox->statuses.back().reason =
        "robot(s) " + lost.str() + lost_for +
        (left < static_cast<std::size_t>(spec.leader_number)
             ? std::string(": fewer robots than leaders left")
             : ": " + std::to_string(left) + " robots left, fewer than mission_min_robots " +
                   std::to_string(params_.min_robots));
    return;
  }

  // A member newly lost: the first leader says so at once, with its phase again (a progress
  // report: /flock/mission/progress), and the mission goes on without it.
  if (live->lost.size() > live->lost_told && live->phase >= MissionPhase::kGathering &&
      live->phase <= MissionPhase::kUnloading) {
    live->lost_told = live->lost.size();
    outbox->statuses.push_back(Report(*live, inside));
    outbox->statuses.back().reason =
        "robot(s) " + lost.str() + lost_for + ": the mission goes on without them";
  }

  switch (live->phase) {
    case MissionPhase::kGathering: {
      if (inside == left &&
          (!params_.transport.gather_one_chain || group.OneChain(params_.local_range_m))) {
        // Balloon spreading: the robots spread under the object first, frozen later.
        live->spread_frozen = params_.loading_spread == LoadingSpread::kNone;
        live->spread_end_tick = tick + static_cast<std::uint64_t>(params_.loading_spread_ticks);
        if (live->spread_frozen) outbox->freeze = spec.AssignedRuns();
        EnterPhase(live, MissionPhase::kLoading, tick, inside, outbox);
        if (!live->lost.empty()) {
          outbox->statuses.back().reason = "without robot(s) " + lost.str() +
                                           " (lost: not heard for " +
                                           std::to_string(params_.lost_after_ticks) + " ticks)";
        }
      } else if (periodic) {
        outbox->statuses.push_back(Report(*live, inside));
      }
      break;
    }
    case MissionPhase::kLoading:
      if (periodic) outbox->statuses.push_back(Report(*live, inside));
      if (!live->spread_frozen) {
        // Spread done: everyone stands from the next tick on; the transport starts after it,
        // so every robot anchors the object to positions that no longer change.
        if (tick >= live->spread_end_tick) {
          live->spread_frozen = true;
          outbox->freeze = spec.AssignedRuns();
        }
        break;
      }
      if (live->loaded && tick >= live->signal_tick &&
          (params_.loading_spread == LoadingSpread::kNone || tick > live->spread_end_tick)) {
        outbox->resume = spec.AssignedRuns();
        live->transport_ticks = 0;
        EnterPhase(live, MissionPhase::kTransport, tick, inside, outbox);
        // Anchored now, on the positions every robot will anchor to at the next tick.
        Group anchor = group;
        UpdateCentre(live, self, &anchor);
      }
      break;
    case MissionPhase::kTransport: {
      ++live->transport_ticks;
      if (Distance(live->centre, spec.target) <= params_.goal_tolerance_m) {
        outbox->update_object = std::make_pair(spec.id, live->centre);
        outbox->freeze = spec.AssignedRuns();
        EnterPhase(live, MissionPhase::kUnloading, tick, inside, outbox);
      } else {
        if (live->transport_ticks % static_cast<std::uint64_t>(params_.object_update_ticks) == 0) {
          outbox->update_object = std::make_pair(spec.id, live->centre);
        }
        if (periodic) outbox->statuses.push_back(Report(*live, inside));
      }
      break;
    }
    case MissionPhase::kUnloading:
      if (periodic) outbox->statuses.push_back(Report(*live, inside));
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
  tick_ = tick;
  MissionPlan plan;
  // A robot its mission counts lost (its first leader's status named it, or it missed its
  // ticks) is no member of it any more: the others go on without it, so it leaves, and its
  // object is a danger zone for it as any other mission's. Carrying on beside them, it kept an
  // object of its own making (rejecting the first leader's updates as jumps) and stood in
  // their way, and it held its next mission back until the lost one ended (a partition of its
  // host during TRANSPORT).
  queue_.erase(std::remove_if(queue_.begin(), queue_.end(),
                              [this](std::uint16_t id) {
                                const Live& live = live_.at(id);
                                return !live.spec.LeaderOnly() && live.lost.count(self_id_) > 0;
                              }),
               queue_.end());
  if (!queue_.empty()) plan.active = queue_.front();
  if (plan.active) {
    Live& live = live_.at(*plan.active);
    const MissionSpec& spec = live.spec;
    Group group;
    bool lost_now = false;  // a member was lost this tick
    if (!spec.LeaderOnly()) {
      const bool first_before = LeadsFirst(live);
      lost_now = Heartbeats(&live, heard, tick);
      // Robots a status named lost since the last tick count as lost now.
      lost_now = std::exchange(live.lost_heard, false) || lost_now;
      if (lost_now) {
        if (live.anchored) live.reanchor = true;
        if (!first_before && LeadsFirst(live)) {
          // Promoted: it takes over the phase machine from the next tick on (a robot node in
          // real time that never led connects its mission publishers first).
          live.promoted = true;
          live.first_since = tick;
        }
      }
      group = Locate(live, self, heard);
      UpdateCentre(&live, self, &group);
    }
    if (outbox != nullptr && LeadsFirst(live) && (!live.promoted || tick > live.first_since)) {
      RunFirstLeader(&live, self, group, tick, outbox);
    }
    if (spec.LeaderOnly()) {
      if (spec.IsLeader(self_id_) && !live.self_arrived) {
        plan.lead = true;
        plan.keep_flock = true;
        plan.goal = spec.target;
        plan.steer = Bearing(self.position, spec.target);
      }
    } else {
      // Its swarm is its mission group [THESIS_CODE 1].
      plan.group.only = true;
      plan.group.ids = spec.Assigned();
      Carry carry;
      carry.transport = live.phase >= MissionPhase::kTransport && live.anchored;
      carry.loading = live.phase == MissionPhase::kLoading;
      carry.mode = static_cast<TransportMode>(spec.transport_mode);
      const std::vector<std::uint16_t> leaders = LeadersNow(live);
      carry.leader = std::find(leaders.begin(), leaders.end(), self_id_) != leaders.end();
      carry.centre = live.centre;
      carry.object = spec.ObjectAt(live.centre);
      // Along its route around the static danger zones: the next waypoint, passed within reach
      // (the target itself ends the transport as before).
      while (live.leg + 1 < live.route.size() &&
             Distance(live.centre, live.route[live.leg]) <= params_.waypoint_reach_m) {
        ++live.leg;
      }
      carry.target = live.route.empty() ? spec.target : live.route[live.leg];
      carry.goal_tolerance_m = params_.goal_tolerance_m;
      carry.formation_offset = live.place;
      if (!carry.transport) Gather(&live, self, heard, tick, lost_now, &carry);
      carry.leaders = leaders;
      std::sort(carry.leaders.begin(), carry.leaders.end());
      for (std::uint16_t id : plan.group.ids) {
        if (id != self_id_) carry.peers.push_back(id);
      }
      plan.carry = carry;
    }
  }
  if (!plan.carry) {
    // Idle (or leading alone): the robots of others' transport missions are not its swarm.
    for (const auto& kv : live_) {
      if (kv.second.spec.LeaderOnly()) continue;
      for (std::uint16_t id : kv.second.spec.Assigned()) plan.group.ids.push_back(id);
    }
    std::sort(plan.group.ids.begin(), plan.group.ids.end());
    plan.group.ids.erase(std::unique(plan.group.ids.begin(), plan.group.ids.end()),
                         plan.group.ids.end());
  }
  for (const auto& kv : live_) {
    const Live& live = kv.second;
    if (live.spec.LeaderOnly()) continue;  // a leader-only mission has no object
    const bool active = plan.active && *plan.active == kv.first;
    // Its own object binds its robots as CarryStep says (a robot outside drives for its
    // centre over any ground, as in the thesis's code: held to "no deeper outside" it could be
    // wedged at the rim for good); the leader of a leader-only mission has none.
    if (active && plan.carry) continue;
    Zone zone;
    zone.id = live.spec.id;
    zone.shape = live.spec.ObjectAt(live.centre);
    // Its own active object is safety (all else is danger); any other object is danger.
    zone.inverted = active;
    plan.zones.push_back(zone);
  }
  return plan;
}

}  // namespace core
}  // namespace swarm_transport
