#include "swarm_transport/core/mission_agent.h"

#include <algorithm>
#include <cmath>
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
  live.centre_tick = tick_;
  if (!mission.LeaderOnly()) {
    live.route = ObjectRoute(mission, params_.static_zones, params_.world_size_m)
                     .value_or(std::vector<Vec2>{mission.target});
  }
  live_.emplace(mission.id, live);
  if (mission.Assigns(self_id_)) queue_.push_back(mission.id);
  return true;
}

bool MissionAgent::OnObjectUpdate(std::uint16_t mission_id, Vec2 centre, std::string* why) {
  auto it = live_.find(mission_id);
  if (it == live_.end()) {
    *why = "object update for unknown mission " + std::to_string(mission_id);
    return false;
  }
  Live& live = it->second;
  const double size = params_.world_size_m;
  if (!(centre.x >= 0.0 && centre.y >= 0.0 && centre.x <= size && centre.y <= size)) {
    std::ostringstream os;
    os << "object update " << mission_id << ": (" << centre.x << ", " << centre.y
       << ") is outside the arena [0, " << size << "]";
    *why = os.str();
    return false;
  }
  // Relayed in the round of the tick after the one it was sent in.
  const std::uint64_t ticks = tick_ + 1 - std::min(tick_ + 1, live.centre_tick);
  const double jump = Distance(centre, live.centre);
  if (jump > MaxObjectStep(ticks, params_.speed_m_per_tick)) {
    std::ostringstream os;
    os << "object update " << mission_id << ": a jump of " << jump << " m in " << ticks
       << " tick(s) is farther than its robots can carry it";
    *why = os.str();
    return false;
  }
  live.centre = centre;
  live.centre_tick = tick_ + 1;
  // In transport the object is its robots' centroid plus the offset each anchored; the first
  // leader's is the mission's (it reports and publishes it): UpdateCentre takes it.
  if (live.anchored && !LeadsFirst(live)) live.leader_centre = centre;
  return true;
}

double MaxObjectStep(std::uint64_t ticks, double speed_m_per_tick) {
  return (2.0 * static_cast<double>(ticks) + 2.0) * speed_m_per_tick;
}

Vec2 InsideArena(Vec2 centre, Vec2 size, double world_size_m) {
  if (!(world_size_m > 0.0)) return centre;
  const auto axis = [world_size_m](double c, double extent) {
    const double half = extent / 2.0;
    if (!(half * 2.0 <= world_size_m)) return c;
    return std::clamp(c, half, world_size_m - half);
  };
  return Vec2{axis(centre.x, size.x), axis(centre.y, size.y)};
}

bool MissionAgent::OnObjectDelete(std::uint16_t mission_id, std::string* why) {
  if (live_.count(mission_id) == 0) {
    *why = "object delete for unknown mission " + std::to_string(mission_id);
    return false;
  }
  Drop(mission_id);
  return true;
}

bool MissionAgent::OnEvent(std::uint16_t mission_id, MissionEventKind event,
                           std::uint64_t not_before_tick, std::string* why) {
  auto it = live_.find(mission_id);
  if (it == live_.end()) {
    *why = "signal for unknown mission " + std::to_string(mission_id);
    return false;
  }
  Live& live = it->second;
  if (!LeadsFirst(live)) {
    // Only the first leader acts on it; the others keep it in case they are promoted (it may
    // arrive before the status of the phase it belongs to).
    (event == MissionEventKind::kLoaded ? live.loaded : live.unloaded) = true;
    live.signal_tick = not_before_tick;
    return true;
  }
  const MissionPhase expected =
      event == MissionEventKind::kLoaded ? MissionPhase::kLoading : MissionPhase::kUnloading;
  if (live.phase != expected) {
    *why = std::string("signal ") + (event == MissionEventKind::kLoaded ? "LOADED" : "UNLOADED") +
           " for mission " + std::to_string(mission_id) + " in phase " + PhaseName(live.phase) +
           " (expected " + PhaseName(expected) + ")";
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

void MissionAgent::OnStatus(std::uint16_t mission_id, MissionPhase phase,
                            const std::vector<std::uint16_t>& lost) {
  auto it = live_.find(mission_id);
  if (it == live_.end()) return;
  Live& live = it->second;
  if (!live.spec.LeaderOnly()) {
    // Its first leader's lost robots are lost here too (for good, as its own): a robot that is
    // named leaves the mission's lead, and one that leads now because of them was promoted.
    const bool first_before = LeadsFirst(live);
    for (std::uint16_t id : lost) {
      if (live.spec.Assigns(id) && live.lost.insert(id).second) {
        live.last_seen.erase(id);
        live.lost_heard = true;
      }
    }
    if (live.lost_heard && !first_before && LeadsFirst(live)) {
      live.promoted = true;
      live.first_since = tick_;
    }
  }
  if (LeadsFirst(live)) return;
  // QUEUED and REJECTED come from the dispatcher (a REJECTED may name a live mission's id when
  // a duplicate was refused): only the first leader's phases move a mission on.
  if (phase == MissionPhase::kQueued || phase == MissionPhase::kRejected) return;
  // Phases only move forward; a late or repeated report must not turn the clock back.
  if (static_cast<int>(phase) > static_cast<int>(it->second.phase)) {
    it->second.phase = phase;
    it->second.phase_tick = tick_ + 1;  // relayed: it began in the tick before this one's
  }
}

const MissionSpec* MissionAgent::Find(std::uint16_t mission_id) const {
  const auto it = live_.find(mission_id);
  return it == live_.end() ? nullptr : &it->second.spec;
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
  return std::any_of(live_.begin(), live_.end(),
                     [this](const auto& kv) { return LeadsFirst(kv.second); });
}

std::set<std::uint16_t> MissionAgent::LostOf(std::uint16_t mission_id) const {
  const auto it = live_.find(mission_id);
  return it == live_.end() ? std::set<std::uint16_t>() : it->second.lost;
}

std::vector<std::uint16_t> MissionAgent::Left(const Live& live) const {
  std::vector<std::uint16_t> left;
  for (std::uint16_t id : live.spec.Assigned()) {
    if (live.lost.count(id) == 0) left.push_back(id);
  }
  return left;
}

std::vector<std::uint16_t> MissionAgent::LeadersNow(const Live& live) const {
  if (live.lost.empty()) return live.spec.Leaders();
  // In the order they lead (the named leaders first): a lost leader's place goes to the next.
  std::vector<std::uint16_t> leaders;
  for (std::uint16_t id : live.spec.LeadOrder()) {
    if (live.lost.count(id) == 0) leaders.push_back(id);
  }
  if (live.spec.leader_number >= 0 &&
      static_cast<std::size_t>(live.spec.leader_number) < leaders.size()) {
    leaders.resize(static_cast<std::size_t>(live.spec.leader_number));
  }
  return leaders;
}

bool MissionAgent::LeadsFirst(const Live& live) const {
  if (live.lost.empty()) return live.spec.FirstLeader() == self_id_;
  for (std::uint16_t id : live.spec.LeadOrder()) {
    if (live.lost.count(id) == 0) return id == self_id_;
  }
  return false;
}

bool MissionAgent::Heartbeats(Live* live, const std::vector<Neighbour>& heard, std::uint64_t tick) {
  const MissionSpec& spec = live->spec;
  const std::size_t lost_before = live->lost.size();
  // A robot that missed ticks for as long (hung, then resumed) was lost for the others where its
  // radio fell silent with it: it counts itself lost too, so that it does not lead beside the
  // one promoted in its place (MissionAgentParams::heard_while_hung).
  const auto self = live->heard_tick.find(self_id_);
  if (!params_.heard_while_hung && self != live->heard_tick.end() &&
      tick - self->second > params_.lost_after_ticks) {
    live->lost.insert(self_id_);
  }
  // A member never heard counts from the mission's first tick.
  for (std::uint16_t member : spec.Assigned()) live->heard_tick.emplace(member, tick);
  live->heard_tick[self_id_] = tick;
  for (const Neighbour& n : heard) {
    if (n.type != 0 || !spec.Assigns(n.id)) continue;
    live->heard_tick[n.id] = tick;
    live->last_seen[n.id] = n.position;
  }
  for (const auto& kv : live->heard_tick) {
    if (kv.first != self_id_ && tick - kv.second > params_.lost_after_ticks) {
      live->lost.insert(kv.first);
    }
  }
  for (std::uint16_t id : live->lost) live->last_seen.erase(id);
  return live->lost.size() != lost_before;
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
  r.lost.assign(live.lost.begin(), live.lost.end());
  return r;
}

void MissionAgent::EnterPhase(Live* live, MissionPhase phase, std::uint64_t tick,
                              std::uint16_t inside, MissionOutbox* outbox) {
  live->phase = phase;
  live->phase_tick = tick;
  outbox->statuses.push_back(Report(*live, inside));
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

void StatusSequencer::Sequence(bool ready, std::vector<StatusReport>* statuses,
                               std::vector<StatusReport>* progress) {
  // A mission's QUEUED goes out before any other status of it (a leader-only mission may end in
  // the tick it starts).
  if (!queued_.empty() && (ready || !statuses->empty())) {
    statuses->insert(statuses->begin(), queued_.begin(), queued_.end());
    queued_.clear();
  }
  std::size_t kept = 0;
  for (std::size_t i = 0; i < statuses->size(); ++i) {
    StatusReport& r = (*statuses)[i];
    const auto last = reported_.find(r.mission_id);
    if (last != reported_.end() && last->second == r.phase) {
      progress->push_back(std::move(r));
      continue;
    }
    if (r.phase == MissionPhase::kDone || r.phase == MissionPhase::kAborted) {
      reported_.erase(r.mission_id);  // its last word (the id may be used again)
    } else {
      reported_[r.mission_id] = r.phase;
    }
    if (kept != i) (*statuses)[kept] = std::move(r);
    ++kept;
  }
  statuses->resize(kept);
}

}  // namespace core
}  // namespace swarm_transport
