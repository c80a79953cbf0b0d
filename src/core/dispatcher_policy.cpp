#include "swarm_transport/core/dispatcher_policy.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>

namespace swarm_transport {
namespace core {

DispatcherPolicy::DispatcherPolicy(DispatcherPolicyParams params, DispatcherOutlet* outlet)
    : params_(std::move(params)), outlet_(outlet), book_(params_.book) {}

void DispatcherPolicy::Log(bool warn, const char* format, ...) {
  char text[1024];
  va_list args;
  va_start(args, format);
  std::vsnprintf(text, sizeof(text), format, args);
  va_end(args);
  outlet_->Log(warn, text);
}

void DispatcherPolicy::SetFileMissions(std::vector<MissionSpec> missions,
                                       std::vector<std::uint64_t> at_ticks) {
  at_ticks.resize(missions.size(), 0);
  file_missions_ = std::move(missions);
  file_ticks_ = std::move(at_ticks);
}

std::set<std::uint16_t> DispatcherPolicy::KnownRobots() const {
  std::set<std::uint16_t> known;
  for (const auto& kv : swarm_) known.insert(kv.first);
  return known;
}

std::map<std::uint16_t, PlannerRobot> DispatcherPolicy::IdleRobots() const {
  std::set<std::uint16_t> busy;
  for (const auto& kv : book_.entries()) {
    if (kv.second.Live() && kv.second.has_spec) {
      for (std::uint16_t id : kv.second.spec.Assigned()) busy.insert(id);
    }
  }
  std::map<std::uint16_t, PlannerRobot> idle;
  for (const auto& kv : swarm_) {
    if (busy.count(kv.first) == 0 && unreachable_.count(kv.first) == 0) idle.insert(kv);
  }
  return idle;
}

MissionBook::Verdict DispatcherPolicy::Submit(MissionSpec spec, const std::string& source,
                                              bool auto_id, bool publish,
                                              std::uint64_t start_tick) {
  return Submit(std::move(spec), source, auto_id, publish, start_tick, KnownRobots());
}

MissionBook::Verdict DispatcherPolicy::Refuse(MissionSpec spec, const std::string& source,
                                              const std::string& why) {
  MissionBook::Verdict refused;
  refused.id = spec.id;
  refused.reason = why;
  refused.message = "mission " + std::to_string(spec.id) + " rejected: " + why;
  refused.spec = std::move(spec);
  Log(true, "rejected mission %u from %s: %s", refused.id, source.c_str(), why.c_str());
  outlet_->Rejected(refused.spec, why);
  return refused;
}

MissionBook::Verdict DispatcherPolicy::Submit(MissionSpec spec, const std::string& source,
                                              bool auto_id, bool publish, std::uint64_t start_tick,
                                              const std::set<std::uint16_t>& robots) {
  if (spec.recruit) return StartRecruit(std::move(spec), source, auto_id, start_tick);
  if (spec.robot_count > 0 && spec.robot_ids.empty() && spec.range_from >= spec.range_to) {
    // A count-only order: the robots are picked by the selection matrix (SPEC 9.10); the order
    // goes out with their ids. Nothing is picked from a swarm the dispatcher has not heard yet.
    std::string why = PickRobotsByCount(&spec, IdleRobots(), params_.selection);
    if (!why.empty() && !has_swarm_) {
      why += " (no robot positions heard yet: a dispatcher just started; submit it again soon)";
    }
    if (!why.empty() && !unreachable_.empty()) {
      std::string ids;
      for (std::uint16_t id : unreachable_) ids += (ids.empty() ? "" : ", ") + std::to_string(id);
      why += " (not counted: robot(s) " + ids + ", whose process is not connected to the orders)";
    }
    if (!why.empty()) return Refuse(std::move(spec), source, why);
    Log(false, "mission %u from %s: robot_count picked robots %s", spec.id, source.c_str(),
        DescribeMission(spec).c_str());
  }
  MissionBook::Verdict verdict =
      book_.Submit(std::move(spec), source, auto_id, !publish, robots, params_.clock());
  if (!verdict.accepted) {
    Log(true, "rejected mission %u from %s: %s", verdict.id, source.c_str(),
        verdict.reason.c_str());
    outlet_->Rejected(verdict.spec, verdict.reason);
    return verdict;
  }
  if (verdict.attached) {
    Log(false, "mission %u from %s: its first leader had reported it already", verdict.id,
        source.c_str());
    return verdict;
  }
  // No QUEUED status from here: the mission's first leader reports it when it holds the order,
  // and every later phase too, so that a subscriber gets them in order over one connection (a
  // QUEUED of the dispatcher's raced the first leader's GATHERING, issue 9).
  if (publish) outlet_->Order(verdict.spec, start_tick);
  Log(false, "queued mission %u from %s: %s", verdict.id, source.c_str(),
      DescribeMission(verdict.spec).c_str());
  return verdict;
}

MissionBook::Verdict DispatcherPolicy::StartRecruit(MissionSpec spec, const std::string& source,
                                                    bool auto_id, std::uint64_t start_tick) {
  if (auto_id && spec.id == 0) {
    do {
      spec.id = book_.NextFreeId();
    } while (recruiting_.count(spec.id) > 0);
  }
  std::set<std::uint16_t> idle;
  for (const auto& kv : IdleRobots()) idle.insert(kv.first);
  MissionContext context = book_.Context(KnownRobots());
  for (const auto& kv : recruiting_) context.live_missions.insert(kv.first);
  std::string why = ValidateRecruit(spec, idle, context);
  if (why.empty() && recruiting_.size() >= kMaxRecruiting) {
    why = "already " + std::to_string(kMaxRecruiting) + " missions recruit";
  }
  const int max_live = params_.book.max_live_missions;
  if (why.empty() && book_.LiveCount() + static_cast<int>(recruiting_.size()) >= max_live) {
    why = "already " + std::to_string(max_live) + " live missions";
  }
  if (!why.empty()) return Refuse(std::move(spec), source, why);
  std::set<std::uint16_t> statists_used;
  for (const auto& kv : recruiting_) statists_used.insert(kv.second.statist_id);
  std::uint16_t statist_id = kRecruitStatistId;
  while (statists_used.count(statist_id) > 0) --statist_id;
  Recruiting r{spec, RecruitWatch(spec), source, 0, statist_id};
  const std::uint64_t now_tick = has_swarm_ ? swarm_tick_ : 0;
  r.start_tick = start_tick > now_tick ? start_tick : now_tick + 1;
  recruiting_.emplace(spec.id, r);
  MissionBook::Verdict verdict;
  verdict.id = spec.id;
  verdict.spec = spec;
  verdict.accepted = true;
  verdict.message = "mission " + std::to_string(spec.id) + " recruiting: a statist at (" +
                    std::to_string(spec.object_centre.x) + ", " +
                    std::to_string(spec.object_centre.y) + ") gathers " +
                    std::to_string(spec.robot_count) + " robots";
  if (params_.lockstep) {
    // The simulator places the statist from the answer at its start tick (the file missions'
    // answer carries it at the first positions).
    if (file_missions_scheduled_) SendAnswer({});
  } else {
    outlet_->StatistUp(statist_id, spec.object_centre, kRecruitStatistCopies);
  }
  const std::string from =
      params_.lockstep ? " from tick " + std::to_string(r.start_tick) : std::string();
  Log(false, "mission %u from %s recruits %u robots with a statist at (%.3f, %.3f)%s", spec.id,
      source.c_str(), spec.robot_count, spec.object_centre.x, spec.object_centre.y, from.c_str());
  return verdict;
}

void DispatcherPolicy::SendAnswer(std::vector<std::pair<std::uint16_t, std::uint64_t>> orders,
                                  std::vector<core::Signal> events,
                                  std::optional<StatusKey> status) {
  DispatcherAnswer answer;
  answer.has_positions = has_swarm_;
  answer.checked_tick = swarm_tick_;
  answer.status = status;
  answer.orders = std::move(orders);
  answer.events = std::move(events);
  // Before its first positions the file missions are not scheduled yet: tick 1 on waits. A
  // recruit watches the positions of every tick after its statist's first (its order may enter
  // the next tick).
  answer.hold_from_tick = has_swarm_ ? 0 : 1;
  for (const auto& kv : recruiting_) {
    const Recruiting& r = kv.second;
    answer.recruiting.push_back(
        {kv.first, r.statist_id, r.spec.object_centre, kRecruitStatistCopies, r.start_tick});
    if (answer.hold_from_tick == 0 || r.start_tick + 1 < answer.hold_from_tick) {
      answer.hold_from_tick = r.start_tick + 1;
    }
  }
  outlet_->Answer(answer);
}

std::vector<std::pair<std::uint16_t, std::uint64_t>> DispatcherPolicy::WatchRecruits() {
  std::vector<std::pair<std::uint16_t, std::uint64_t>> due;
  if (recruiting_.empty()) return due;
  std::map<std::uint16_t, Vec2> idle;
  for (const auto& kv : IdleRobots()) idle[kv.first] = kv.second.position;
  for (auto it = recruiting_.begin(); it != recruiting_.end();) {
    Recruiting& r = it->second;
    // Lock-step: its statist stands from its start tick; the robots before it are not watched.
    if ((params_.lockstep && swarm_tick_ < r.start_tick) || !r.watch.Observe(idle)) {
      ++it;
      continue;
    }
    const std::vector<std::uint16_t> recruits = r.watch.Recruits();
    for (std::uint16_t id : recruits) idle.erase(id);  // not for another recruit of this tick
    MissionSpec order = RecruitedOrder(r.spec, recruits);
    std::string first;
    for (std::size_t i = 0; i < recruits.size(); ++i) {
      first += (i ? "," : "") + std::to_string(recruits[i]);
    }
    Log(false,
        "mission %u: %zu robots inside its object at tick %llu (first in: %s); its statist is "
        "deleted",
        order.id, recruits.size(), static_cast<unsigned long long>(swarm_tick_), first.c_str());
    if (!params_.lockstep) outlet_->StatistDown(r.statist_id, kRecruitStatistCopies);
    const std::string source = r.source;
    it = recruiting_.erase(it);
    // The robots take the order at the next tick (lock-step), entering GATHERING inside the
    // object; they freeze for LOADING as in every mission.
    const std::uint64_t start = params_.lockstep ? swarm_tick_ + 1 : 0;
    const MissionBook::Verdict verdict = Submit(order, source, false, true, start);
    if (verdict.accepted && params_.lockstep) due.emplace_back(verdict.id, start);
  }
  return due;
}

void DispatcherPolicy::SetSwarm(std::uint64_t tick, std::map<std::uint16_t, PlannerRobot> robots) {
  swarm_ = std::move(robots);
  swarm_tick_ = tick;
  has_swarm_ = true;
}

std::vector<std::pair<std::uint64_t, double>> DispatcherPolicy::OnSwarm(
    std::uint64_t tick, std::map<std::uint16_t, PlannerRobot> robots) {
  SetSwarm(tick, std::move(robots));
  std::vector<std::pair<std::uint64_t, double>> later;
  if (params_.lockstep) {
    // Every positions is answered (even without a file: a lock-step simulator holds tick 1 for
    // the first answer), with the file missions at the first and the recruits' orders.
    std::vector<std::pair<std::uint16_t, std::uint64_t>> orders;
    if (!file_missions_scheduled_) {
      orders = ScheduleFileMissions();
      file_missions_scheduled_ = true;
    }
    for (const auto& order : WatchRecruits()) orders.push_back(order);
    SendAnswer(std::move(orders));
    return later;
  }
  WatchRecruits();
  if (file_missions_scheduled_ || file_missions_.empty()) return later;
  file_missions_scheduled_ = true;
  // Each group of file missions after its at_tick's worth of time (0: start_delay_s).
  for (const std::uint64_t at_tick :
       std::set<std::uint64_t>(file_ticks_.begin(), file_ticks_.end())) {
    const double delay_s = at_tick > 0 ? static_cast<double>(at_tick) * params_.book.tick_period_s
                                       : params_.start_delay_s;
    if (delay_s <= 0.0) {
      SubmitFileMissions(at_tick);
    } else {
      later.emplace_back(at_tick, delay_s);
    }
  }
  return later;
}

void DispatcherPolicy::SubmitFileMissions(std::uint64_t at_tick) {
  for (std::size_t i = 0; i < file_missions_.size(); ++i) {
    if (file_ticks_[i] == at_tick) Submit(file_missions_[i], "missions_file", true, true);
  }
}

std::vector<std::pair<std::uint16_t, std::uint64_t>> DispatcherPolicy::ScheduleFileMissions() {
  // The tick of start_delay_s from the run's start, and never one that has begun.
  const auto delay_ticks = static_cast<std::uint64_t>(
      std::ceil(params_.start_delay_s / params_.book.tick_period_s - 1e-9));
  std::vector<std::pair<std::uint16_t, std::uint64_t>> due;
  for (std::size_t i = 0; i < file_missions_.size(); ++i) {
    // A mission's own at_tick, else start_delay_s; never a tick that has begun.
    const std::uint64_t start =
        std::max<std::uint64_t>(swarm_tick_ + 1, file_ticks_[i] > 0 ? file_ticks_[i] : delay_ticks);
    // Checked against the robots of its start tick: those of now, with the spawns and kills
    // of the simulator's events until then (a scenario's robot that joins later can be named).
    const std::set<std::uint16_t> robots =
        params_.robots_at ? params_.robots_at(KnownRobots(), start) : KnownRobots();
    const MissionBook::Verdict verdict =
        Submit(file_missions_[i], "missions_file", true, true, start, robots);
    if (!verdict.accepted || recruiting_.count(verdict.id) > 0) continue;  // a recruit: below
    due.emplace_back(verdict.id, start);
    Log(false, "file mission %u enters the run at tick %llu", verdict.id,
        static_cast<unsigned long long>(start));
  }
  file_missions_.clear();
  return due;
}

MissionBook::StatusOutcome DispatcherPolicy::OnStatus(const MissionReport& report,
                                                      const std::string& from) {
  MissionBook::StatusOutcome outcome = book_.OnStatus(report, params_.clock());
  if (outcome.followed) {
    Log(false, "following mission %u first seen in a status from %s", report.mission_id,
        from.c_str());
  }
  if (outcome.entered) {
    const MissionBook::Entry& m = *book_.Find(report.mission_id);
    Log(false, "mission %u is %s%s%s", report.mission_id, PhaseName(m.phase),
        m.reason.empty() ? "" : ": ", m.reason.c_str());
  }
  for (const core::Signal& due : outcome.signals) outlet_->Event(due, "with the configured delay");
  if (params_.lockstep) {
    SendAnswer({}, outcome.signals, StatusKey{report.mission_id, report.phase, report.tick});
  }
  return outcome;
}

MissionBook::StatusOutcome DispatcherPolicy::OnResent(const MissionReport& report,
                                                      const MissionSpec* order,
                                                      const std::string& from) {
  MissionBook::StatusOutcome outcome = book_.Restore(report, order, params_.clock());
  if (outcome.followed) {
    Log(false, "mission %u rebuilt from its re-sent %s status (from %s)%s", report.mission_id,
        PhaseName(report.phase), from.c_str(),
        book_.Find(report.mission_id) != nullptr && book_.Find(report.mission_id)->has_spec
            ? " with its order"
            : " without its order");
  } else if (outcome.entered) {
    Log(false, "mission %u is %s (a re-sent status from %s)", report.mission_id,
        PhaseName(report.phase), from.c_str());
  }
  for (const core::Signal& due : outcome.signals) {
    outlet_->Event(due, "due in the re-sent phase, with the configured delay");
  }
  return outcome;
}

void DispatcherPolicy::SkipStatus(const StatusKey& status) {
  if (params_.lockstep) SendAnswer({}, {}, status);
}

std::string DispatcherPolicy::Signal(std::uint16_t mission_id, MissionEventKind kind) {
  std::string why;
  if (kind != MissionEventKind::kLoaded && kind != MissionEventKind::kUnloaded) {
    why =
        "event must be 1 (LOADED) or 2 (UNLOADED) but is " + std::to_string(static_cast<int>(kind));
  } else {
    why = book_.Signal(mission_id, kind, params_.clock());
  }
  if (!why.empty()) {
    Log(true, "refused a signal: %s", why.c_str());
    return why;
  }
  outlet_->Event(core::Signal{mission_id, kind, 0}, "requested through ~signal");
  return why;
}

void DispatcherPolicy::Watchdog(double wall_s, double grace_s) {
  const double now_s = params_.clock();
  // Real time: a LOADED / UNLOADED a robot may have missed goes again while its mission stands
  // in the phase it was sent for (lock-step delivers every signal in its round).
  if (!params_.lockstep && params_.signal_resend_s > 0.0) {
    for (const core::Signal& owed : book_.Owed(now_s, params_.signal_resend_s)) {
      outlet_->Event(owed, "again: its mission is still in the phase it was sent for");
    }
  }
  std::map<std::uint16_t, double> still_silent;
  for (const auto& silent : book_.Silent(now_s)) {
    const std::uint16_t id = silent.first;
    // Silent in sim time may only mean that its status waits in the caller's queue: a fast
    // lock-step (10,000 ticks/s in one process) passes 300 ticks in 30 ms of wall time. A
    // mission is ended only when it is still silent after grace_s of wall time.
    const auto seen = silent_since_.find(id);
    const double since = seen == silent_since_.end() ? wall_s : seen->second;
    still_silent[id] = since;
    if (wall_s - since < grace_s) continue;
    const MissionSpec spec = book_.Find(id)->spec;
    if (!book_.Abort(id, silent.second, now_s)) continue;
    Log(true, "mission %u ABORTED: %s", id, silent.second.c_str());
    // Its robots drop the mission and its object (and those frozen for it move again).
    outlet_->Aborted(spec, silent.second);
    still_silent.erase(id);
  }
  silent_since_ = std::move(still_silent);
}

std::string DispatcherPolicy::Table() const {
  std::string table = book_.Table(params_.clock());
  // The tick of the poses it picks robots from (a count-only order): a test that holds the run
  // waits for it instead of sleeping.
  if (has_swarm_) table += "positions of tick " + std::to_string(swarm_tick_) + "\n";
  return table;
}

}  // namespace core
}  // namespace swarm_transport
