#include "swarm_transport/core/run_metrics.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <utility>

namespace swarm_transport {
namespace core {
namespace {

// Sample times this close to due count as due (sim_time is tick * tick_period in floats).
constexpr double kSampleEpsS = 1e-9;

std::size_t PhaseIndex(MissionPhase phase) { return static_cast<std::size_t>(phase); }

std::string Num(double value) {
  if (!std::isfinite(value)) return "";
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", value);
  return buffer;
}

std::string Num(std::uint64_t value) { return std::to_string(value); }

template <typename T>
std::string Opt(const std::optional<T>& value) {
  return value ? Num(*value) : "";
}

std::string NotFollowing(std::uint16_t id, std::size_t followed) {
  return "not following mission " + std::to_string(id) + ": " + std::to_string(followed) +
         " missions followed already";
}

}  // namespace

const char RunMetrics::kSwarmHeader[] = "tick,sim_time_s,robots,swarm_count,largest_swarm";
const char RunMetrics::kMissionsHeader[] =
    "mission_id,kind,assigned,leaders,final_state,queued_tick,gathering_tick,loading_tick,"
    "transport_tick,unloading_tick,done_tick,transport_ticks,slip_per_robot_m,"
    "distance_per_robot_m,leader_waits,path_fraction_attached,leader_swarm_at_arrival,"
    "object_error_m,leader_contact,loading_nn_cv";
const char RunMetrics::kRunHeader[] =
    "run_name,seed,robots,ticks,sim_time_s,samples,mean_swarm_count,final_swarm_count,"
    "missions_done,missions_aborted,coverage_fraction,nn_spacing_mean_m,nn_spacing_cv";

long MetricsFrame::IndexOf(std::uint16_t id) const {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  return it != ids.end() && *it == id ? it - ids.begin() : -1;
}

std::size_t RunMetrics::HistoryCapacity(std::size_t robots) {
  return std::clamp(kHistoryPositions / std::max<std::size_t>(robots, 1), kMinHistoryFrames,
                    kMaxHistoryFrames);
}

RunMetrics::RunMetrics(RunMetricsParams params, Log log) : params_(params), log_(std::move(log)) {}

void RunMetrics::Say(Level level, const std::string& text) const {
  if (log_) log_(level, text);
}

std::size_t RunMetrics::missions_unfinished() const {
  std::size_t unfinished = 0;
  for (const auto& kv : missions_) unfinished += kv.second.final_state ? 0 : 1;
  return unfinished;
}

bool RunMetrics::AddFrame(MetricsFrame frame, std::optional<SwarmSample>* sample) {
  if (sample != nullptr) sample->reset();
  if (!history_.empty() && frame.tick <= history_.back().tick) return false;
  history_.push_back(std::move(frame));
  const std::size_t capacity = HistoryCapacity(history_.back().positions.size());
  const double newest_wall_s = history_.back().wall_s;
  const auto too_old = [this, newest_wall_s](const MetricsFrame& oldest) {
    return params_.history_wall_s > 0.0 && newest_wall_s > 0.0 && oldest.wall_s > 0.0 &&
           newest_wall_s - oldest.wall_s > params_.history_wall_s;
  };
  while (history_.size() > capacity || (history_.size() > 1 && too_old(history_.front()))) {
    // The oldest frame leaves: windows whose end is not known yet take it in now.
    FeedMissions(false, history_.front().tick);
    history_.pop_front();
  }
  std::optional<SwarmSample> due = SampleIfDue(history_.back());
  if (sample != nullptr) *sample = due;
  FeedMissions(false);
  WriteFinished(false);
  return true;
}

std::optional<SwarmSample> RunMetrics::SampleIfDue(const MetricsFrame& frame) {
  if (first_sample_time_s_ && frame.sim_time_s + kSampleEpsS < next_sample_time_s_) {
    return std::nullopt;
  }
  if (!first_sample_time_s_) first_sample_time_s_ = frame.sim_time_s;
  // Due times stay on the grid first + k * period; a jump skips the missed ones.
  const double since = frame.sim_time_s - *first_sample_time_s_;
  const double k = std::floor((since + kSampleEpsS) / params_.sample_period_s) + 1.0;
  next_sample_time_s_ = *first_sample_time_s_ + k * params_.sample_period_s;

  const SwarmComponents swarms(frame.positions, params_.local_range_m);
  ++samples_;
  swarm_count_sum_ += static_cast<double>(swarms.SwarmCount());
  std::size_t live = 0;
  for (const auto& kv : missions_) live += kv.second.final_state ? 0 : 1;

  SwarmSample sample;
  sample.tick = frame.tick;
  sample.sim_time_s = frame.sim_time_s;
  sample.robots = frame.positions.size();
  sample.swarm_count = swarms.SwarmCount();
  sample.largest_swarm = swarms.LargestSwarm();
  sample.live_missions = live;
  return sample;
}

std::string RunMetrics::SwarmRow(const SwarmSample& sample) {
  return Num(sample.tick) + "," + Num(sample.sim_time_s) + "," +
         Num(static_cast<std::uint64_t>(sample.robots)) + "," +
         Num(static_cast<std::uint64_t>(sample.swarm_count)) + "," +
         Num(static_cast<std::uint64_t>(sample.largest_swarm));
}

// Only a full table of missions is a "why not" (what the recorder warns about); a duplicate
// order for a live id (the dispatcher rejects it: the first is kept) is no news.
std::string RunMetrics::AddOrder(const MissionSpec& spec, std::uint64_t start_tick) {
  // Known from the tick it reached us, or (lock-step) from the later tick it is stamped with.
  const std::uint64_t newest = std::max<std::uint64_t>(newest_tick(), start_tick);
  written_.erase(spec.id);  // a finished mission's id is used again
  auto it = missions_.find(spec.id);
  if (it != missions_.end()) {
    MissionRecord& m = it->second;
    // Its status came first (the order is latched and may arrive later): attach the order.
    // A second order for a live id is a duplicate the dispatcher rejects: keep the first.
    if (!m.has_spec && !m.final_state) {
      m.spec = spec;
      m.has_spec = true;
      if (!m.known_tick) m.known_tick = newest;
      FeedMissions(false);
      WriteFinished(false);
    }
    return "";
  }
  if (missions_.size() >= kMaxMissions) return NotFollowing(spec.id, missions_.size());
  MissionRecord& m = missions_[spec.id];
  m.spec = spec;
  m.has_spec = true;
  m.known_tick = newest;
  return "";
}

// As AddOrder, only a full table of missions is a "why not": a REJECTED, late news of a
// finished mission and an end with nothing before it are taken (and leave nothing).
std::string RunMetrics::AddStatus(std::uint16_t mission_id, MissionPhase phase, std::uint64_t tick,
                                  Vec2 object) {
  auto it = missions_.find(mission_id);
  if (phase == MissionPhase::kRejected) {
    // A rejected order (a raw order the dispatcher refused) is forgotten; a REJECTED
    // naming a mission that was accepted (QUEUED or later) is about a refused duplicate of
    // its id, and the accepted one goes on.
    if (it != missions_.end() && !it->second.final_state) {
      const auto& entered = it->second.entered;
      const bool accepted =
          std::any_of(entered.begin(), entered.end(), [](const auto& t) { return t.has_value(); });
      if (!accepted) missions_.erase(it);
    }
    return "";
  }
  if (written_.count(mission_id) > 0) {
    if (phase != MissionPhase::kQueued) return "";  // late news of a mission already written
    written_.erase(mission_id);                     // its id is used again
  }
  if (it == missions_.end()) {
    // An end with neither order nor phases before it leaves nothing to record.
    if (phase == MissionPhase::kDone || phase == MissionPhase::kAborted) return "";
    if (missions_.size() >= kMaxMissions) return NotFollowing(mission_id, missions_.size());
    it = missions_.emplace(mission_id, MissionRecord()).first;
  }
  MissionRecord& m = it->second;
  if (m.final_state) return "";  // late news of a finished mission
  // Every phase, QUEUED included, is reported by the mission's first leader with its tick, 0
  // included (taking the newest frame instead put a GATHERING of tick 0 at tick 64 when frames
  // came in first).
  auto& entered = m.entered[PhaseIndex(phase)];
  if (!entered) entered = tick;
  m.object = object;
  if (phase == MissionPhase::kDone || phase == MissionPhase::kAborted) m.final_state = phase;
  FeedMissions(false);
  WriteFinished(false);
  return "";
}

void RunMetrics::Drain() {
  FeedMissions(true);
  WriteFinished(true);
}

// A mission's metrics are fed from the kept frames inside its window (start, end] once the
// window's end is known, or a frame when it leaves the history (HistoryCapacity frames), so a
// status that arrives after later frames still cuts the window at its own tick (in lock-step
// at thousands of ticks per second, hundreds of frames may come first). A transport's window
// is TRANSPORT .. UNLOADING. A leader-only mission's runs from its order (the leader leads as
// soon as it holds it; its first status may come much later, see
// MissionPublishers::Ready) to its DONE, or to the first tick the leader is within
// goal_tolerance_m of the target - the leader's own arrival test, which also stands for a DONE
// that was lost.
std::optional<std::uint64_t> RunMetrics::WindowStart(const MissionRecord& m) {
  if (!m.has_spec) return std::nullopt;
  const auto& e = m.entered;
  if (!m.spec.LeaderOnly()) return e[PhaseIndex(MissionPhase::kTransport)];
  // A leader-only mission starts with its order: the leader leads as soon as it holds it.
  std::optional<std::uint64_t> start = m.known_tick;
  for (MissionPhase p :
       {MissionPhase::kQueued, MissionPhase::kGathering, MissionPhase::kTransport}) {
    const auto& tick = e[PhaseIndex(p)];
    if (tick && (!start || *tick < *start)) start = tick;
  }
  return start;
}

std::optional<std::uint64_t> RunMetrics::WindowEnd(const MissionRecord& m) {
  std::vector<MissionPhase> ends = {MissionPhase::kDone, MissionPhase::kAborted};
  // A transport ends at arrival, when the first leader reports UNLOADING.
  if (m.has_spec && !m.spec.LeaderOnly()) ends.push_back(MissionPhase::kUnloading);
  std::optional<std::uint64_t> end = m.arrival_tick;
  for (MissionPhase p : ends) {
    const auto& tick = m.entered[PhaseIndex(p)];
    if (tick && (!end || *tick < *end)) end = tick;
  }
  return end;
}

// Feeds every mission the kept frames it is due: all of them when its window's end is known or
// `drain` (the run is over), else those up to tick `through` (a frame leaving the history),
// else none.
void RunMetrics::FeedMissions(bool drain, std::optional<std::uint64_t> through) {
  if (history_.empty()) return;
  const std::uint64_t newest = history_.back().tick;
  for (auto& kv : missions_) {
    MissionRecord& m = kv.second;
    const auto start = WindowStart(m);
    if (!start) continue;
    std::uint64_t limit = 0;
    if (drain || WindowEnd(m)) {
      limit = newest;
    } else if (through) {
      limit = *through;
    } else {
      continue;
    }
    if (!m.fed_through && history_.front().tick > *start && !m.warned_history) {
      m.warned_history = true;
      Say(Level::kWarn, "mission " + std::to_string(kv.first) + " began at tick " +
                            std::to_string(*start) + ", before the oldest kept frame (tick " +
                            std::to_string(history_.front().tick) + "); its metrics start there");
    }
    for (const MetricsFrame& frame : history_) {
      // The end may become known while feeding (a leader's arrival).
      const auto end = WindowEnd(m);
      if (frame.tick > limit || (end && frame.tick > *end)) break;
      if (frame.tick < *start || (m.fed_through && frame.tick <= *m.fed_through)) continue;
      Feed(kv.first, &m, frame);
      m.fed_through = frame.tick;
    }
  }
}

void RunMetrics::Feed(std::uint16_t id, MissionRecord* m, const MetricsFrame& frame) {
  const MissionSpec& spec = m->spec;
  bool complete = true;
  if (spec.LeaderOnly()) {
    const long leader = frame.IndexOf(spec.FirstLeader());
    complete = leader >= 0;
    if (complete) {
      if (!m->leader) m->leader.emplace(spec.target, params_.local_range_m);
      m->leader->Feed(frame.tick, frame.positions, static_cast<std::size_t>(leader));
      if (!m->arrival_tick && m->leader->DistanceToTarget() <= params_.goal_tolerance_m) {
        m->arrival_tick = frame.tick;
        if (!m->final_state) {
          // Its DONE is on the way, or was lost (published before we were connected).
          char tolerance[32];
          std::snprintf(tolerance, sizeof(tolerance), "%.3f", params_.goal_tolerance_m);
          Say(Level::kInfo, "mission " + std::to_string(id) + ": leader " +
                                std::to_string(spec.FirstLeader()) + " within " + tolerance +
                                " m of its target at tick " + std::to_string(frame.tick) +
                                ": done");
          m->final_state = MissionPhase::kDone;
          auto& done = m->entered[PhaseIndex(MissionPhase::kDone)];
          if (!done) done = frame.tick;
        }
      }
    }
  } else {
    const std::vector<std::uint16_t> assigned = spec.Assigned();
    std::vector<Vec2> positions;
    std::vector<bool> leaders;
    positions.reserve(assigned.size());
    leaders.reserve(assigned.size());
    for (std::uint16_t robot : assigned) {
      const long index = frame.IndexOf(robot);
      if (index < 0) {
        complete = false;
        break;
      }
      positions.push_back(frame.positions[static_cast<std::size_t>(index)]);
      leaders.push_back(spec.IsLeader(robot));
    }
    if (complete) {
      // Contact = within the local range, where a passive robot can align with a leader.
      if (!m->transport.started()) {
        m->transport = TransportTracker(params_.local_range_m);
        // How evenly loading left them (SPEC 9.5 loading_spread): at the transport's first frame.
        m->loading_nn_cv = DispersionOf(positions, params_.world_size_m, params_.coverage_radius_m,
                                        params_.coverage_cell_m)
                               .nn_cv;
      }
      m->transport.Feed(frame.tick, positions, leaders);
    }
  }
  if (!complete && !m->warned_missing) {
    m->warned_missing = true;
    Say(Level::kWarn, "mission " + std::to_string(id) +
                          ": a robot of the mission is missing from /flock/world_poses at tick " +
                          std::to_string(frame.tick) + "; such ticks are skipped");
  }
}

// Writes (into rows_) and forgets finished missions whose frames are all in; `drain`: all of
// them.
void RunMetrics::WriteFinished(bool drain) {
  const std::uint64_t newest = newest_tick();
  for (auto it = missions_.begin(); it != missions_.end();) {
    const MissionRecord& m = it->second;
    const auto start = WindowStart(m);
    const auto end = WindowEnd(m);
    // Its metrics are complete when every frame up to the window's end is in.
    const bool ready = m.final_state && (drain || !start || (end && newest >= *end));
    if (!ready) {
      ++it;
      continue;
    }
    std::string row = MissionRow(it->first, m);
    Say(Level::kInfo, "mission " + std::to_string(it->first) + " " +
                          core::PhaseName(*m.final_state) + ": " + row);
    if (m.recovered) rows_.push_back(RecoveredComment(it->first));
    rows_.push_back(std::move(row));
    written_.insert(it->first);
    rows_of_.insert(it->first);
    (*m.final_state == MissionPhase::kDone ? missions_done_ : missions_aborted_) += 1;
    it = missions_.erase(it);
  }
}

std::vector<std::string> RunMetrics::TakeMissionRows() {
  std::vector<std::string> rows;
  rows.swap(rows_);
  return rows;
}

std::string RunMetrics::MissionRow(std::uint16_t id, const MissionRecord& m) const {
  const bool done = m.final_state && *m.final_state == MissionPhase::kDone;
  const bool leader_only = m.has_spec && m.spec.LeaderOnly();
  const char* kind = !m.has_spec ? "unknown" : leader_only ? "leader" : "transport";
  std::string transport_ticks, slip, distance, waits, fraction, swarm, error, contact, spacing;
  if (m.has_spec && !leader_only) {
    if (m.transport.started()) {
      transport_ticks = Num(m.transport.ticks());
      slip = Num(m.transport.SlipPerRobot());
      distance = Num(m.transport.DistancePerRobot());
      waits = Num(m.transport.LeaderWaits());
      if (const auto c = m.transport.LeaderContact()) contact = Num(*c);
      if (m.loading_nn_cv) spacing = Num(*m.loading_nn_cv);
    }
    if (m.object) error = Num(Distance(*m.object, m.spec.target));
  } else if (leader_only && m.leader) {
    waits = Num(m.leader->LeaderWaits());
    error = Num(m.leader->DistanceToTarget());
    if (done) {
      fraction = Num(m.leader->PathFractionAttached());
      swarm = Num(static_cast<std::uint64_t>(m.leader->SwarmAtLastTick()));
    }
  }
  const auto& e = m.entered;
  std::ostringstream row;
  row << id << "," << kind << ","
      << (m.has_spec ? Num(static_cast<std::uint64_t>(m.spec.Assigned().size())) : "") << ","
      << (m.has_spec ? Num(static_cast<std::uint64_t>(m.spec.Leaders().size())) : "") << ","
      << (m.final_state ? PhaseName(*m.final_state) : "") << ","
      << Opt(e[PhaseIndex(MissionPhase::kQueued)]) << ","
      << Opt(e[PhaseIndex(MissionPhase::kGathering)]) << ","
      << Opt(e[PhaseIndex(MissionPhase::kLoading)]) << ","
      << Opt(e[PhaseIndex(MissionPhase::kTransport)]) << ","
      << Opt(e[PhaseIndex(MissionPhase::kUnloading)]) << ","
      << Opt(e[PhaseIndex(MissionPhase::kDone)]) << "," << transport_ticks << "," << slip << ","
      << distance << "," << waits << "," << fraction << "," << swarm << "," << error << ","
      << contact << "," << spacing;
  return row.str();
}

std::string RunMetrics::RunRow(const std::string& run_name, std::int64_t seed) const {
  std::size_t robots = 0;
  std::size_t final_count = 0;
  std::uint64_t ticks = 0;
  double sim_time_s = 0.0;
  std::optional<Dispersion> spread;
  if (!history_.empty()) {
    const MetricsFrame& last = history_.back();
    robots = last.positions.size();
    ticks = last.tick;
    sim_time_s = last.sim_time_s;
    final_count = SwarmComponents(last.positions, params_.local_range_m).SwarmCount();
    spread = DispersionOf(last.positions, params_.world_size_m, params_.coverage_radius_m,
                          params_.coverage_cell_m);
  }
  std::ostringstream row;
  row << run_name << "," << seed << "," << robots << "," << ticks << "," << Num(sim_time_s) << ","
      << samples_ << ","
      << (samples_ > 0 ? Num(swarm_count_sum_ / static_cast<double>(samples_)) : "") << ","
      << final_count << "," << missions_done_ << "," << missions_aborted_ << ","
      << (spread ? Num(spread->coverage_fraction) : "") << ","
      << (spread ? Num(spread->nn_mean_m) : "") << "," << (spread ? Num(spread->nn_cv) : "");
  return row.str();
}

}  // namespace core
}  // namespace swarm_transport
