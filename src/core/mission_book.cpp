#include "swarm_transport/core/mission_book.h"

#include <algorithm>
#include <cstdio>
#include <iomanip>
#include <sstream>

namespace swarm_transport {
namespace core {
namespace {

std::uint16_t Clamp16(std::size_t value) {
  return static_cast<std::uint16_t>(std::min<std::size_t>(value, 65535));
}

}  // namespace

std::string DescribeMission(const MissionSpec& m) {
  std::ostringstream os;
  os << std::setprecision(4);
  const std::vector<std::uint16_t> assigned = m.Assigned();
  os << assigned.size() << (assigned.size() == 1 ? " robot " : " robots ");
  if (m.robot_ids.empty()) {
    os << "[" << m.range_from << ", " << m.range_to << ")";
  } else {
    constexpr std::size_t kShown = 10;
    os << "{";
    for (std::size_t i = 0; i < assigned.size() && i < kShown; ++i) {
      os << (i > 0 ? ", " : "") << assigned[i];
    }
    os << (assigned.size() > kShown ? ", ...}" : "}");
  }
  os << ", " << m.leader_number << " leader(s)";
  if (!m.leader_ids.empty()) {  // named (a count-only mission's: the front ones)
    const std::vector<std::uint16_t> leaders = m.Leaders();
    os << " {";
    for (std::size_t i = 0; i < leaders.size(); ++i) os << (i > 0 ? ", " : "") << leaders[i];
    os << "}";
  }
  os << ", first leader " << m.FirstLeader() << ", ";
  if (m.LeaderOnly()) {
    os << "leader-only to (" << m.target.x << ", " << m.target.y << ")";
  } else {
    os << m.object_size.x << " x " << m.object_size.y << " object at (" << m.object_centre.x << ", "
       << m.object_centre.y << ") to (" << m.target.x << ", " << m.target.y << "), "
       << (m.transport_mode == 1 ? "formation" : "swarm") << " mode";
  }
  return os.str();
}

bool MissionBook::Entry::Live() const {
  return phase != MissionPhase::kDone && phase != MissionPhase::kAborted &&
         phase != MissionPhase::kRejected;
}

int MissionBook::LiveCount() const {
  int live = 0;
  for (const auto& kv : entries_) live += kv.second.Live() ? 1 : 0;
  return live;
}

const MissionBook::Entry* MissionBook::Find(std::uint16_t id) const {
  const auto it = entries_.find(id);
  return it == entries_.end() ? nullptr : &it->second;
}

MissionContext MissionBook::Context(const std::set<std::uint16_t>& known_robots,
                                    int ignore_id) const {
  MissionContext c;
  c.world_size_m = params_.world_size_m;
  c.known_robots = known_robots;
  c.static_zones = params_.static_zones;
  for (const auto& kv : entries_) {
    if (kv.second.Live() && kv.first != ignore_id) c.live_missions.insert(kv.first);
  }
  return c;
}

std::uint16_t MissionBook::NextFreeId() {
  // The table is bounded far below 65535 entries, so a free id is always found.
  for (int tries = 0; tries < 65535; ++tries) {
    const std::uint16_t id = next_id_;
    next_id_ = next_id_ == 65535 ? 1 : static_cast<std::uint16_t>(next_id_ + 1);
    if (entries_.count(id) == 0) return id;
  }
  return next_id_;
}

MissionBook::Verdict MissionBook::Submit(MissionSpec spec, const std::string& source, bool auto_id,
                                         bool attach, const std::set<std::uint16_t>& known_robots,
                                         double now_s) {
  Verdict verdict;
  const std::uint16_t next_id = next_id_;
  if (auto_id && spec.id == 0) spec.id = NextFreeId();
  verdict.id = spec.id;
  auto it = entries_.find(spec.id);
  // A mission first seen through its leader's status (its order arrived late) gets the order
  // attached instead of a "duplicate id" rejection.
  attach = attach && it != entries_.end() && it->second.Live() && !it->second.has_spec;
  // An attached order is live already: it is checked, not admitted again.
  MissionContext context = Context(known_robots, attach ? spec.id : -1);
  if (!attach) context.max_live_missions = params_.max_live_missions;
  const std::string reason = AdmitMission(spec, context);
  verdict.spec = spec;
  if (!reason.empty()) {
    next_id_ = next_id;  // a rejected mission does not use up an automatic id
    verdict.reason = reason;
    verdict.message = "mission " + std::to_string(spec.id) + " rejected: " + reason;
    return verdict;
  }
  verdict.accepted = true;
  if (attach) {
    it->second.spec = spec;
    it->second.has_spec = true;
    it->second.source = source;
    verdict.attached = true;
    verdict.message = "mission " + std::to_string(spec.id) + " (already running) attached";
    return verdict;
  }
  if (it != entries_.end()) {
    // A finished mission's id is reused: its entry and its place in the finished list go.
    const auto old = std::make_pair(it->first, it->second.generation);
    finished_.erase(std::remove(finished_.begin(), finished_.end(), old), finished_.end());
    entries_.erase(it);
  }
  Entry& m = entries_[spec.id];
  m.spec = spec;
  m.has_spec = true;
  m.source = source;
  m.generation = next_generation_++;
  m.robots_assigned = Clamp16(spec.Assigned().size());
  if (!spec.LeaderOnly()) m.distance_to_target_m = Distance(spec.object_centre, spec.target);
  m.phase = MissionPhase::kQueued;
  m.heard_s = now_s;
  m.entered[static_cast<std::size_t>(MissionPhase::kQueued)] = now_s;
  m.reached = 1u << static_cast<unsigned>(MissionPhase::kQueued);
  verdict.message = "mission " + std::to_string(spec.id) + " queued: " + DescribeMission(spec);
  return verdict;
}

MissionBook::StatusOutcome MissionBook::OnStatus(const MissionReport& report, double now_s) {
  StatusOutcome out;
  const MissionPhase phase = report.phase;
  auto it = entries_.find(report.mission_id);
  if (it != entries_.end() && !it->second.Live()) {
    out.ignored = "late news of a finished mission";
    return out;
  }
  if (it == entries_.end()) {
    if (phase == MissionPhase::kRejected) {
      // A REJECTED from elsewhere is about a submission, not about a mission to follow.
      out.ignored = "a REJECTED of a mission not followed";
      return out;
    }
    if (LiveCount() >= params_.max_live_missions) {
      out.ignored = "too many live missions";
      return out;
    }
    // A mission whose order the dispatcher missed (e.g. it started later): follow it anyway.
    Entry& m = entries_[report.mission_id];
    m.source = "status";
    m.generation = next_generation_++;
    m.spec.id = report.mission_id;
    it = entries_.find(report.mission_id);
    out.followed = true;
  } else if (phase == MissionPhase::kRejected && it->second.phase != MissionPhase::kQueued) {
    // Someone rejected a duplicate of a running mission's id: the running one goes on.
    out.ignored = "a REJECTED of a duplicate of a running mission";
    return out;
  }
  Entry& m = it->second;
  if (report.robots_assigned > 0) m.robots_assigned = report.robots_assigned;
  m.robots_inside = report.robots_inside;
  m.distance_to_target_m = report.distance_to_target_m;
  m.heard_s = now_s;
  if (report.tick > 0) m.phase_tick = report.tick;
  if (!report.reason.empty()) m.reason = report.reason;
  if (phase != m.phase || m.reached == 0) {
    EnterPhase(report.mission_id, &m, phase, now_s, &out.signals);
    out.entered = true;
  }
  return out;
}

MissionBook::StatusOutcome MissionBook::Restore(const MissionReport& report,
                                                const MissionSpec* order, double now_s) {
  const std::uint16_t id = report.mission_id;
  if (id != 0 && id != 65535 && id >= next_id_) next_id_ = static_cast<std::uint16_t>(id + 1);
  auto it = entries_.find(id);
  if (it != entries_.end() && it->second.Live() && report.phase < it->second.phase) {
    StatusOutcome out;
    out.ignored = "an earlier phase than the one followed";
    return out;
  }
  StatusOutcome out = OnStatus(report, now_s);
  it = entries_.find(id);
  if (it == entries_.end()) return out;
  Entry& m = it->second;
  if (out.followed) m.source = "resent";
  if (order != nullptr && order->id == id && !m.has_spec && (out.followed || m.Live())) {
    m.spec = *order;
    m.has_spec = true;
    if (report.robots_assigned == 0) m.robots_assigned = Clamp16(order->Assigned().size());
  }
  return out;
}

void MissionBook::OnProgress(const MissionReport& report, double now_s) {
  auto it = entries_.find(report.mission_id);
  if (it == entries_.end() || !it->second.Live()) return;
  Entry& m = it->second;
  m.heard_s = now_s;
  // A progress report with a reason says why (a robot lost, the mission going on without it):
  // `mission status` shows it.
  if (!report.reason.empty()) m.reason = report.reason;
  if (report.robots_assigned > 0) m.robots_assigned = report.robots_assigned;
  m.robots_inside = report.robots_inside;
  m.distance_to_target_m = report.distance_to_target_m;
}

void MissionBook::EnterPhase(std::uint16_t id, Entry* m, MissionPhase phase, double now_s,
                             std::vector<core::Signal>* signals) {
  const auto index = static_cast<unsigned>(phase);
  m->phase = phase;
  if ((m->reached & (1u << index)) == 0) {
    m->reached |= 1u << index;
    m->entered[index] = now_s;
  }
  // Sent at once, stamped with the first leader's tick at which it takes effect: the delay
  // then lands on the same tick whatever the scheduling (lock-step runs reproduce).
  const auto due = [&](MissionEventKind kind, double delay_s, bool* sent) {
    if (delay_s < 0.0 || *sent) return;
    signals->push_back({id, kind, SignalTick(m->phase_tick, delay_s, params_.tick_period_s)});
    *sent = true;
    m->signal_s = now_s;
    m->signal_tick = signals->back().not_before_tick;
  };
  if (phase == MissionPhase::kLoading) {
    due(MissionEventKind::kLoaded, params_.loaded_delay_s, &m->loaded_sent);
  }
  if (phase == MissionPhase::kUnloading) {
    due(MissionEventKind::kUnloaded, params_.unloaded_delay_s, &m->unloaded_sent);
  }
  if (!m->Live()) {
    finished_.emplace_back(id, m->generation);
    Forget();  // never the mission just finished: it is the newest
  }
}

std::vector<core::Signal> MissionBook::Owed(double now_s, double after_s) {
  std::vector<core::Signal> owed;
  for (auto& kv : entries_) {
    Entry& m = kv.second;
    const bool loading = m.phase == MissionPhase::kLoading && m.loaded_sent;
    const bool unloading = m.phase == MissionPhase::kUnloading && m.unloaded_sent;
    if ((!loading && !unloading) || now_s - m.signal_s < after_s) continue;
    owed.push_back({kv.first, loading ? MissionEventKind::kLoaded : MissionEventKind::kUnloaded,
                    m.signal_tick});
    m.signal_s = now_s;
  }
  return owed;
}

std::vector<std::pair<std::uint16_t, std::string>> MissionBook::Silent(double now_s) const {
  std::vector<std::pair<std::uint16_t, std::string>> silent;
  if (params_.silent_after_s < 0.0) return silent;
  for (const auto& kv : entries_) {
    const Entry& m = kv.second;
    // QUEUED waits its turn (its first leader reports nothing until it starts).
    const bool running = m.phase >= MissionPhase::kGathering && m.phase <= MissionPhase::kUnloading;
    if (!running || now_s - m.heard_s <= params_.silent_after_s) continue;
    std::ostringstream why;
    why << "first leader";
    if (m.has_spec) why << " (robot " << m.spec.FirstLeader() << ")";
    why << " silent for " << std::setprecision(4) << now_s - m.heard_s << " s in "
        << PhaseName(m.phase) << " (last report at its tick " << m.phase_tick
        << "): lost; the mission ends";
    silent.emplace_back(kv.first, why.str());
  }
  return silent;
}

bool MissionBook::Abort(std::uint16_t mission_id, const std::string& reason, double now_s) {
  auto it = entries_.find(mission_id);
  if (it == entries_.end() || !it->second.Live()) return false;
  it->second.reason = reason;
  std::vector<core::Signal> none;
  EnterPhase(mission_id, &it->second, MissionPhase::kAborted, now_s, &none);
  return true;
}

std::string MissionBook::Signal(std::uint16_t mission_id, MissionEventKind kind, double now_s) {
  const std::string mission = "mission " + std::to_string(mission_id);
  auto it = entries_.find(mission_id);
  if (it == entries_.end()) return mission + " is unknown";
  if (!it->second.Live()) {
    return mission + " is finished (" + PhaseName(it->second.phase) + ")";
  }
  (kind == MissionEventKind::kLoaded ? it->second.loaded_sent : it->second.unloaded_sent) = true;
  it->second.signal_s = now_s;  // sent now, to take effect at once (as a repeat does)
  it->second.signal_tick = 0;
  return "";
}

void MissionBook::Forget() {
  while (finished_.size() > kMaxFinishedMissions) {
    const auto oldest = finished_.front();
    finished_.pop_front();
    auto it = entries_.find(oldest.first);
    if (it != entries_.end() && it->second.generation == oldest.second && !it->second.Live()) {
      entries_.erase(it);
    }
  }
}

std::string MissionBook::Table(double now_s) const {
  std::ostringstream os;
  os << entries_.size() << " mission(s) tracked, " << LiveCount() << " live\n";
  if (entries_.empty()) return os.str();
  char line[160];
  std::snprintf(line, sizeof(line), "%-6s %-10s %-14s %6s %6s %8s  %s\n", "id", "state", "source",
                "robots", "inside", "dist_m", "seconds per phase | reason");
  os << line;
  static const char* const kShort[] = {"Q", "G", "L", "T", "U"};
  for (const auto& kv : entries_) {
    const Entry& m = kv.second;
    const std::string source = m.source.substr(0, m.source.find(' '));
    std::snprintf(line, sizeof(line), "%-6u %-10s %-14s %6u %6u %8.2f ", kv.first,
                  PhaseName(m.phase), source.c_str(), m.robots_assigned, m.robots_inside,
                  m.distance_to_target_m);
    os << line;
    // Each phase lasts from its entry to the entry of the next phase reached (or until now).
    for (unsigned p = 0; p <= static_cast<unsigned>(MissionPhase::kUnloading); ++p) {
      if ((m.reached & (1u << p)) == 0) continue;
      double end = now_s;
      for (unsigned q = p + 1; q < kPhaseCount; ++q) {
        if (m.reached & (1u << q)) {
          end = m.entered[q];
          break;
        }
      }
      std::snprintf(line, sizeof(line), " %s %.1f", kShort[p], end - m.entered[p]);
      os << line;
    }
    if (!m.reason.empty()) os << " | " << m.reason;
    os << "\n";
  }
  return os.str();
}

}  // namespace core
}  // namespace swarm_transport
