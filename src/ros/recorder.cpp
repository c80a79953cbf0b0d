#include "swarm_transport/ros/recorder.h"

#include <ros/callback_queue.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <sstream>
#include <system_error>
#include <utility>

#include "swarm_transport/Swarm_Stats.h"
#include "swarm_transport/ros/conversions.h"
#include "swarm_transport/ros/names.h"

namespace swarm_transport {
namespace {

using core::MissionPhase;
using XmlRpc::XmlRpcValue;

constexpr char kNode[] = "recorder";
// /flock/positions comes every tick and a slow recorder must not lose lock-step ticks: the
// queue holds many ticks (the simulator does not wait for observers once it runs).
constexpr std::uint32_t kPositionsQueue = 10000;
constexpr std::uint32_t kMissionQueue = 1000;
constexpr std::uint32_t kStatsQueue = 10;
// Wall seconds between two warnings of one kind.
constexpr double kWarnPeriodS = 10.0;
// Sample times this close to due count as due (sim_time is tick * tick_period in floats).
constexpr double kSampleEpsS = 1e-9;
// Spin period of Run() (wall s): how long a stop request may wait.
constexpr double kSpinS = 0.05;

constexpr char kSwarmHeader[] = "tick,sim_time_s,robots,swarm_count,largest_swarm";
constexpr char kMissionsHeader[] =
    "mission_id,kind,assigned,leaders,final_state,queued_tick,gathering_tick,loading_tick,"
    "transport_tick,unloading_tick,done_tick,transport_ticks,slip_per_robot_m,"
    "distance_per_robot_m,leader_waits,path_fraction_attached,leader_swarm_at_arrival,"
    "object_error_m,leader_contact";
constexpr char kRunHeader[] =
    "run_name,seed,robots,ticks,sim_time_s,samples,mean_swarm_count,final_swarm_count,"
    "missions_done,missions_aborted";

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

std::uint16_t Clamp16(std::size_t value) {
  return static_cast<std::uint16_t>(std::min<std::size_t>(value, 65535));
}

}  // namespace

volatile std::sig_atomic_t Recorder::stop_requested_ = 0;

std::string RecorderParams::Validate() const {
  std::ostringstream os;
  if (!std::isfinite(sample_period_s) || sample_period_s <= 0.0) {
    os << "~sample_period_s must be finite and > 0 (s of sim time) but is " << sample_period_s;
  } else if (run_name.empty() || run_name == "." || run_name == ".." ||
             run_name.find_first_of("/,\"\n\r") != std::string::npos) {
    // It names a directory and is written into run.csv unquoted.
    os << "~run_name must be a file name without '/', ',', '\"' or line breaks but is '" << run_name
       << "'";
  }
  return os.str();
}

CsvFile::~CsvFile() { Close(); }

bool CsvFile::Open(const std::string& path, const std::string& header, std::string* error) {
  Close();
  file_ = std::fopen(path.c_str(), "w");
  if (file_ == nullptr) {
    *error = "cannot write " + path + ": " + std::strerror(errno);
    return false;
  }
  if (!Append(header)) {
    *error = "cannot write " + path;
    Close();
    return false;
  }
  return true;
}

bool CsvFile::Append(const std::string& row) {
  if (file_ == nullptr) return false;
  const bool ok = std::fputs(row.c_str(), file_) >= 0 && std::fputc('\n', file_) != EOF;
  return std::fflush(file_) == 0 && ok;
}

void CsvFile::Close() {
  if (file_ != nullptr) std::fclose(file_);
  file_ = nullptr;
}

long Recorder::Frame::IndexOf(std::uint16_t id) const {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  return it != ids.end() && *it == id ? it - ids.begin() : -1;
}

Recorder::Recorder(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh) {}

void Recorder::RequestStop() { stop_requested_ = 1; }

bool Recorder::LoadParams(std::string* error) {
  XmlRpcValue swarm;
  if (nh_.getParam("/swarm", swarm) && !ConfigFromXmlRpc(swarm, &params_.swarm, error)) {
    *error = "/swarm: " + *error;
    return false;
  }
  params_.seed = static_cast<std::int64_t>(params_.swarm.seed);
  if (!ReadPrivate(private_nh_, "output_dir", &params_.output_dir, error) ||
      !ReadPrivate(private_nh_, "run_name", &params_.run_name, error) ||
      !ReadPrivate(private_nh_, "sample_period_s", &params_.sample_period_s, error)) {
    return false;
  }
  XmlRpcValue seed;
  if (private_nh_.getParam("seed", seed)) {
    if (seed.getType() != XmlRpcValue::TypeInt) {
      *error = "~seed must be an integer";
      return false;
    }
    params_.seed = static_cast<int>(seed);
  }
  *error = params_.Validate();
  return error->empty();
}

bool Recorder::OpenFiles(std::string* error) {
  if (params_.output_dir.empty()) return true;
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path dir = fs::absolute(fs::path(params_.output_dir) / params_.run_name, ec);
  if (!ec) fs::create_directories(dir, ec);
  if (ec) {
    *error = "cannot create the directory " + params_.output_dir + "/" + params_.run_name + ": " +
             ec.message();
    return false;
  }
  run_dir_ = dir.string();
  if (!swarm_csv_.Open(run_dir_ + "/swarm_count.csv", kSwarmHeader, error) ||
      !missions_csv_.Open(run_dir_ + "/missions.csv", kMissionsHeader, error)) {
    return false;
  }
  WriteRun();  // the header and a row of zeros, replaced as the run goes on
  return true;
}

bool Recorder::Initialize() {
  std::string error;
  if (!LoadParams(&error) || !OpenFiles(&error)) {
    ROS_FATAL("%s: %s", kNode, error.c_str());
    return false;
  }
  stats_pub_ = nh_.advertise<Swarm_Stats>(names::kStats, kStatsQueue);
  // Small messages every tick: Nagle's algorithm would batch and delay them.
  positions_sub_ = nh_.subscribe(names::kPositions, kPositionsQueue, &Recorder::OnPositions, this,
                                 ros::TransportHints().tcpNoDelay());
  mission_new_sub_ =
      nh_.subscribe(names::kMissionNew, kMissionQueue, &Recorder::OnMissionNew, this);
  status_sub_ = nh_.subscribe(names::kMissionStatus, kMissionQueue, &Recorder::OnStatus, this,
                              ros::TransportHints().tcpNoDelay());
  ROS_INFO(
      "%s: local range %.3f m, sample every %.3f s of sim time, seed %lld, %s", kNode,
      params_.swarm.flocking.local_range_m, params_.sample_period_s,
      static_cast<long long>(params_.seed),
      run_dir_.empty() ? "no files (~output_dir is empty)" : ("writing to " + run_dir_).c_str());
  return true;
}

void Recorder::Run() {
  ros::CallbackQueue* queue = ros::getGlobalCallbackQueue();
  while (ros::ok() && stop_requested_ == 0) queue->callAvailable(ros::WallDuration(kSpinS));
}

void Recorder::Shutdown() {
  if (shut_down_) return;
  shut_down_ = true;
  positions_sub_.shutdown();
  mission_new_sub_.shutdown();
  status_sub_.shutdown();
  stats_pub_.shutdown();
  FeedMissions(true);
  WriteFinished(true);
  WriteRun();
  swarm_csv_.Close();
  missions_csv_.Close();
  std::size_t unfinished = 0;
  for (const auto& kv : missions_) unfinished += kv.second.final_state ? 0 : 1;
  ROS_INFO("%s: %zu samples up to tick %llu, %zu missions done, %zu aborted, %zu unfinished%s%s",
           kNode, samples_,
           static_cast<unsigned long long>(history_.empty() ? 0 : history_.back().tick),
           missions_done_, missions_aborted_, unfinished, run_dir_.empty() ? "" : "; files in ",
           run_dir_.c_str());
}

bool Recorder::WarnDue(ros::WallTime* last) {
  const ros::WallTime now = ros::WallTime::now();
  if (!last->isZero() && (now - *last).toSec() < kWarnPeriodS) return false;
  *last = now;
  return true;
}

void Recorder::OnPositions(const Robot_Positions::ConstPtr& msg) {
  if (!std::isfinite(msg->sim_time)) {
    if (WarnDue(&last_bad_position_warning_)) {
      ROS_WARN("%s: ignored /flock/positions of tick %llu: sim_time is not finite", kNode,
               static_cast<unsigned long long>(msg->tick));
    }
    return;
  }
  if (!history_.empty() && msg->tick <= history_.back().tick) {
    // The latched message again (a reconnection), or a restarted simulator.
    if (msg->tick < history_.back().tick && WarnDue(&last_tick_warning_)) {
      ROS_WARN(
          "%s: /flock/positions went back from tick %llu to %llu; ignored until it passes "
          "tick %llu again",
          kNode, static_cast<unsigned long long>(history_.back().tick),
          static_cast<unsigned long long>(msg->tick),
          static_cast<unsigned long long>(history_.back().tick));
    }
    return;
  }
  if (!history_.empty() && msg->tick > history_.back().tick + 1 && WarnDue(&last_tick_warning_)) {
    ROS_WARN("%s: missed /flock/positions ticks %llu..%llu (queue overflow or late start)", kNode,
             static_cast<unsigned long long>(history_.back().tick + 1),
             static_cast<unsigned long long>(msg->tick - 1));
  }
  Frame frame;
  frame.tick = msg->tick;
  frame.sim_time_s = msg->sim_time;
  std::vector<std::pair<std::uint16_t, core::Vec2>> robots;
  robots.reserve(msg->robots.size());
  std::size_t bad = 0;
  for (const Robot_Position& r : msg->robots) {
    if (r.type != Robot_Position::TYPE_PHYSICAL) continue;
    if (!std::isfinite(r.pos_x) || !std::isfinite(r.pos_y)) {
      ++bad;
      continue;
    }
    robots.emplace_back(r.robot_id, core::Vec2{r.pos_x, r.pos_y});
  }
  if (bad > 0 && WarnDue(&last_bad_position_warning_)) {
    ROS_WARN("%s: ignored %zu robots with non-finite positions at tick %llu", kNode, bad,
             static_cast<unsigned long long>(msg->tick));
  }
  std::stable_sort(robots.begin(), robots.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& r : robots) {
    if (!frame.ids.empty() && frame.ids.back() == r.first) continue;  // a duplicate id
    frame.ids.push_back(r.first);
    frame.positions.push_back(r.second);
  }
  history_.push_back(std::move(frame));
  const std::size_t capacity = HistoryCapacity(history_.back().positions.size());
  while (history_.size() > capacity) {
    // The oldest frame leaves: windows whose end is not known yet take it in now.
    FeedMissions(false, history_.front().tick);
    history_.pop_front();
  }
  SampleIfDue(history_.back());
  FeedMissions(false);
  WriteFinished(false);
}

void Recorder::SampleIfDue(const Frame& frame) {
  if (first_sample_time_s_ && frame.sim_time_s + kSampleEpsS < next_sample_time_s_) return;
  if (!first_sample_time_s_) first_sample_time_s_ = frame.sim_time_s;
  // Due times stay on the grid first + k * period; a jump skips the missed ones.
  const double since = frame.sim_time_s - *first_sample_time_s_;
  const double k = std::floor((since + kSampleEpsS) / params_.sample_period_s) + 1.0;
  next_sample_time_s_ = *first_sample_time_s_ + k * params_.sample_period_s;

  const core::SwarmComponents swarms(frame.positions, params_.swarm.flocking.local_range_m);
  ++samples_;
  swarm_count_sum_ += static_cast<double>(swarms.SwarmCount());
  std::size_t live = 0;
  for (const auto& kv : missions_) live += kv.second.final_state ? 0 : 1;

  Swarm_Stats stats;
  stats.tick = frame.tick;
  stats.sim_time = frame.sim_time_s;
  stats.robots = Clamp16(frame.positions.size());
  stats.swarm_count = Clamp16(swarms.SwarmCount());
  stats.largest_swarm = Clamp16(swarms.LargestSwarm());
  stats.live_missions = Clamp16(live);
  stats_pub_.publish(stats);

  if (swarm_csv_.is_open()) {
    swarm_csv_.Append(Num(frame.tick) + "," + Num(frame.sim_time_s) + "," +
                      Num(static_cast<std::uint64_t>(frame.positions.size())) + "," +
                      Num(static_cast<std::uint64_t>(swarms.SwarmCount())) + "," +
                      Num(static_cast<std::uint64_t>(swarms.LargestSwarm())));
  }
}

void Recorder::OnMissionNew(const New_Mission::ConstPtr& msg) {
  core::MissionSpec spec = ToMissionSpec(*msg);
  core::MissionContext context;
  context.world_size_m = params_.swarm.flocking.world_size_m;
  const std::string why = core::ValidateMission(spec, context);
  if (!why.empty()) {
    if (WarnDue(&last_bad_mission_warning_)) {
      ROS_WARN("%s: ignored New_Mission %u: %s", kNode, msg->mission_id, why.c_str());
    }
    return;
  }
  // Known from the tick it reached us, or (lock-step) from the later tick it is stamped with.
  const std::uint64_t newest =
      std::max<std::uint64_t>(history_.empty() ? 0 : history_.back().tick, msg->start_tick);
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
    return;
  }
  if (missions_.size() >= kMaxMissions) {
    if (WarnDue(&last_bad_mission_warning_)) {
      ROS_WARN("%s: not following mission %u: %zu missions followed already", kNode, spec.id,
               missions_.size());
    }
    return;
  }
  MissionRecord& m = missions_[spec.id];
  m.spec = spec;
  m.has_spec = true;
  m.known_tick = newest;
}

void Recorder::OnStatus(const Mission_Status::ConstPtr& msg) {
  if (msg->state > Mission_Status::REJECTED || !std::isfinite(msg->object_position_x) ||
      !std::isfinite(msg->object_position_y) || !std::isfinite(msg->distance_to_target)) {
    if (WarnDue(&last_bad_status_warning_)) {
      ROS_WARN(
          "%s: ignored a Mission_Status of mission %u: unknown state %u or a non-finite "
          "field",
          kNode, msg->mission_id, msg->state);
    }
    return;
  }
  const auto phase = static_cast<MissionPhase>(msg->state);
  auto it = missions_.find(msg->mission_id);
  if (phase == MissionPhase::kRejected) {
    // A rejected order (a raw New_Mission the dispatcher refused) is forgotten; a REJECTED
    // naming a mission that was accepted (QUEUED or later) is about a refused duplicate of
    // its id, and the accepted one goes on.
    if (it != missions_.end() && !it->second.final_state) {
      const auto& entered = it->second.entered;
      const bool accepted = std::any_of(entered.begin(), entered.end(),
                                        [](const auto& tick) { return tick.has_value(); });
      if (!accepted) missions_.erase(it);
    }
    return;
  }
  if (written_.count(msg->mission_id) > 0) {
    if (phase != MissionPhase::kQueued) return;  // late news of a mission already written
    written_.erase(msg->mission_id);             // its id is used again
  }
  if (it == missions_.end()) {
    // An end with neither order nor phases before it leaves nothing to record.
    if (phase == MissionPhase::kDone || phase == MissionPhase::kAborted) return;
    if (missions_.size() >= kMaxMissions) {
      if (WarnDue(&last_bad_mission_warning_)) {
        ROS_WARN("%s: not following mission %u: %zu missions followed already", kNode,
                 msg->mission_id, missions_.size());
      }
      return;
    }
    it = missions_.emplace(msg->mission_id, MissionRecord()).first;
  }
  MissionRecord& m = it->second;
  if (m.final_state) return;  // late news of a finished mission
  // Every phase, QUEUED included, is reported by the mission's first leader with its tick, 0
  // included (taking the newest frame instead put a GATHERING of tick 0 at tick 64 when frames
  // came in first).
  const std::uint64_t tick = msg->tick;
  auto& entered = m.entered[PhaseIndex(phase)];
  if (!entered) entered = tick;
  m.object = core::Vec2{msg->object_position_x, msg->object_position_y};
  if (phase == MissionPhase::kDone || phase == MissionPhase::kAborted) m.final_state = phase;
  FeedMissions(false);
  WriteFinished(false);
}

std::optional<std::uint64_t> Recorder::WindowStart(const MissionRecord& m) {
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

std::optional<std::uint64_t> Recorder::WindowEnd(const MissionRecord& m) {
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

std::size_t Recorder::HistoryCapacity(std::size_t robots) {
  return std::clamp(kHistoryPositions / std::max<std::size_t>(robots, 1), kMinHistoryFrames,
                    kMaxHistoryFrames);
}

void Recorder::FeedMissions(bool drain, std::optional<std::uint64_t> through) {
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
      ROS_WARN(
          "%s: mission %u began at tick %llu, before the oldest kept frame (tick %llu); its "
          "metrics start there",
          kNode, kv.first, static_cast<unsigned long long>(*start),
          static_cast<unsigned long long>(history_.front().tick));
    }
    for (const Frame& frame : history_) {
      // The end may become known while feeding (a leader's arrival).
      const auto end = WindowEnd(m);
      if (frame.tick > limit || (end && frame.tick > *end)) break;
      if (frame.tick < *start || (m.fed_through && frame.tick <= *m.fed_through)) continue;
      Feed(&m, frame);
      m.fed_through = frame.tick;
    }
  }
}

void Recorder::Feed(MissionRecord* m, const Frame& frame) {
  const core::MissionSpec& spec = m->spec;
  bool complete = true;
  if (spec.LeaderOnly()) {
    const long leader = frame.IndexOf(spec.FirstLeader());
    complete = leader >= 0;
    if (complete) {
      if (!m->leader) m->leader.emplace(spec.target, params_.swarm.flocking.local_range_m);
      m->leader->Feed(frame.tick, frame.positions, static_cast<std::size_t>(leader));
      if (!m->arrival_tick &&
          m->leader->DistanceToTarget() <= params_.swarm.leader.goal_tolerance_m) {
        m->arrival_tick = frame.tick;
        if (!m->final_state) {
          // Its DONE is on the way, or was lost (published before we were connected).
          ROS_INFO("%s: mission %u: leader %u within %.3f m of its target at tick %llu: done",
                   kNode, spec.id, spec.FirstLeader(), params_.swarm.leader.goal_tolerance_m,
                   static_cast<unsigned long long>(frame.tick));
          m->final_state = MissionPhase::kDone;
          auto& done = m->entered[PhaseIndex(MissionPhase::kDone)];
          if (!done) done = frame.tick;
        }
      }
    }
  } else {
    const std::vector<std::uint16_t> assigned = spec.Assigned();
    std::vector<core::Vec2> positions;
    std::vector<bool> leaders;
    positions.reserve(assigned.size());
    leaders.reserve(assigned.size());
    for (std::uint16_t id : assigned) {
      const long index = frame.IndexOf(id);
      if (index < 0) {
        complete = false;
        break;
      }
      positions.push_back(frame.positions[static_cast<std::size_t>(index)]);
      leaders.push_back(spec.IsLeader(id));
    }
    if (complete) {
      // Contact = within the local range, where a passive robot can align with a leader.
      if (!m->transport.started()) {
        m->transport = core::TransportTracker(params_.swarm.flocking.local_range_m);
      }
      m->transport.Feed(frame.tick, positions, leaders);
    }
  }
  if (!complete && !m->warned_missing) {
    m->warned_missing = true;
    ROS_WARN(
        "%s: mission %u: a robot of the mission is missing from /flock/positions at tick "
        "%llu; such ticks are skipped",
        kNode, spec.id, static_cast<unsigned long long>(frame.tick));
  }
}

void Recorder::WriteFinished(bool drain) {
  const std::uint64_t newest = history_.empty() ? 0 : history_.back().tick;
  bool wrote = false;
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
    WriteMission(it->first, m);
    written_.insert(it->first);
    (*m.final_state == MissionPhase::kDone ? missions_done_ : missions_aborted_) += 1;
    it = missions_.erase(it);
    wrote = true;
  }
  if (wrote && !drain) WriteRun();
}

void Recorder::WriteMission(std::uint16_t id, const MissionRecord& m) {
  const bool done = m.final_state && *m.final_state == MissionPhase::kDone;
  const bool leader_only = m.has_spec && m.spec.LeaderOnly();
  const char* kind = !m.has_spec ? "unknown" : leader_only ? "leader" : "transport";
  std::string transport_ticks, slip, distance, waits, fraction, swarm, error, contact;
  if (m.has_spec && !leader_only) {
    if (m.transport.started()) {
      transport_ticks = Num(m.transport.ticks());
      slip = Num(m.transport.SlipPerRobot());
      distance = Num(m.transport.DistancePerRobot());
      waits = Num(m.transport.LeaderWaits());
      if (const auto c = m.transport.LeaderContact()) contact = Num(*c);
    }
    if (m.object) error = Num(core::Distance(*m.object, m.spec.target));
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
      << (m.final_state ? core::PhaseName(*m.final_state) : "") << ","
      << Opt(e[PhaseIndex(MissionPhase::kQueued)]) << ","
      << Opt(e[PhaseIndex(MissionPhase::kGathering)]) << ","
      << Opt(e[PhaseIndex(MissionPhase::kLoading)]) << ","
      << Opt(e[PhaseIndex(MissionPhase::kTransport)]) << ","
      << Opt(e[PhaseIndex(MissionPhase::kUnloading)]) << ","
      << Opt(e[PhaseIndex(MissionPhase::kDone)]) << "," << transport_ticks << "," << slip << ","
      << distance << "," << waits << "," << fraction << "," << swarm << "," << error << ","
      << contact;
  if (missions_csv_.is_open() && !missions_csv_.Append(row.str())) {
    ROS_ERROR("%s: could not write a row of %s/missions.csv", kNode, run_dir_.c_str());
  }
  ROS_INFO("%s: mission %u %s: %s", kNode, id,
           m.final_state ? core::PhaseName(*m.final_state) : "?", row.str().c_str());
}

void Recorder::WriteRun() {
  if (run_dir_.empty()) return;
  std::size_t robots = 0;
  std::size_t final_count = 0;
  std::uint64_t ticks = 0;
  double sim_time_s = 0.0;
  if (!history_.empty()) {
    const Frame& last = history_.back();
    robots = last.positions.size();
    ticks = last.tick;
    sim_time_s = last.sim_time_s;
    final_count =
        core::SwarmComponents(last.positions, params_.swarm.flocking.local_range_m).SwarmCount();
  }
  std::ostringstream row;
  row << params_.run_name << "," << params_.seed << "," << robots << "," << ticks << ","
      << Num(sim_time_s) << "," << samples_ << ","
      << (samples_ > 0 ? Num(swarm_count_sum_ / static_cast<double>(samples_)) : "") << ","
      << final_count << "," << missions_done_ << "," << missions_aborted_;
  // Written aside and renamed over the old file: a reader never sees half a file.
  const std::string path = run_dir_ + "/run.csv";
  const std::string temporary = path + ".tmp";
  std::string error;
  CsvFile file;
  if (!file.Open(temporary, kRunHeader, &error) || !file.Append(row.str())) {
    ROS_ERROR("%s: %s", kNode,
              error.empty() ? ("cannot write " + temporary).c_str() : error.c_str());
    return;
  }
  file.Close();
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    ROS_ERROR("%s: cannot rename %s to %s: %s", kNode, temporary.c_str(), path.c_str(),
              std::strerror(errno));
  }
}

}  // namespace swarm_transport
