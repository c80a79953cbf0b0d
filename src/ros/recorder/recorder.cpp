#include "swarm_transport/ros/recorder/recorder.h"

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
#include <vector>

#include "swarm_transport/Swarm_Stats.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/diagnostics.h"
#include "swarm_transport/ros/common/mission_resend.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

using core::MissionPhase;
using core::RunMetrics;
using XmlRpc::XmlRpcValue;

constexpr char kNode[] = "recorder";
// /flock/world_poses comes every tick and a slow recorder must not lose lock-step ticks: the
// queue holds many ticks (the simulator does not wait for observers once it runs).
constexpr std::uint32_t kPositionsQueue = 10000;
constexpr std::uint32_t kMissionQueue = 1000;
constexpr std::uint32_t kStatsQueue = 10;
// Wall seconds between two warnings of one kind.
constexpr double kWarnPeriodS = 10.0;
// Spin period of Run() (wall s): how long a stop request may wait.
constexpr double kSpinS = 0.05;
// Wall seconds of frames kept for statuses that come late (RunMetricsParams::history_wall_s).
constexpr double kHistoryWallS = 120.0;

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

core::RunMetricsParams RunMetricsParamsOf(const RecorderParams& params) {
  core::RunMetricsParams metrics;
  metrics.local_range_m = params.swarm.flocking.local_range_m;
  metrics.goal_tolerance_m = params.swarm.leader.goal_tolerance_m;
  metrics.sample_period_s = params.sample_period_s;
  metrics.world_size_m = params.swarm.flocking.world_size_m;
  // Statuses come seconds late (queued messages), not minutes: a frame older than this by the
  // wall clock leaves the history even below its 20,000 frames, which in real time are 33
  // minutes (a recorder that lived an hour grew by them: 53.7 %, session 25's soak). In
  // lock-step at thousands of ticks per second the frame count is the bound, as before.
  metrics.history_wall_s = kHistoryWallS;
  return metrics;
}

core::MetricsFrame RecorderFrame(const Robot_Positions& msg, std::size_t* bad) {
  return RecorderFrame(msg.tick, msg.sim_time, msg.robots, bad);
}

core::MetricsFrame RecorderFrame(std::uint64_t tick, double sim_time,
                                 const std::vector<Robot_Position>& positions, std::size_t* bad) {
  std::vector<core::Position> core_positions;
  core_positions.reserve(positions.size());
  for (const Robot_Position& p : positions) core_positions.push_back(ToPosition(p));
  return core::FrameOf(tick, sim_time, core_positions, bad);
}

std::string RecordOrder(const New_Mission& msg, const SwarmConfig& swarm,
                        core::RunMetrics* metrics) {
  const core::MissionSpec spec = ToMissionSpec(msg);
  core::MissionContext context;
  context.world_size_m = swarm.flocking.world_size_m;
  const std::string why = core::ValidateMission(spec, context);
  if (!why.empty()) {
    return "ignored New_Mission " + std::to_string(msg.mission_id) + ": " + why;
  }
  return metrics->AddOrder(spec, msg.start_tick);
}

std::string RecordStatus(const Mission_Status& msg, core::RunMetrics* metrics) {
  return RecordStatus(ToStatusReport(msg), msg.tick, metrics);
}

std::string RecordStatus(const core::StatusReport& status, std::uint64_t tick,
                         core::RunMetrics* metrics) {
  if (status.phase > core::MissionPhase::kRejected || !std::isfinite(status.object.x) ||
      !std::isfinite(status.object.y) || !std::isfinite(status.distance_to_target)) {
    return "ignored a Mission_Status of mission " + std::to_string(status.mission_id) +
           ": unknown state " + std::to_string(static_cast<int>(status.phase)) +
           " or a non-finite field";
  }
  return metrics->AddStatus(status.mission_id, status.phase, tick, status.object);
}

bool WriteRunFile(const std::string& run_dir, const std::string& row, std::string* error) {
  const std::string path = run_dir + "/run.csv";
  const std::string temporary = path + ".tmp";
  CsvFile file;
  if (!file.Open(temporary, RunMetrics::kRunHeader, error) || !file.Append(row) || !file.Close()) {
    if (error->empty()) *error = "cannot write " + temporary;
    return false;
  }
  if (std::rename(temporary.c_str(), path.c_str()) != 0) {
    *error = "cannot rename " + temporary + " to " + path + ": " + std::strerror(errno);
    return false;
  }
  return true;
}

CsvFile::~CsvFile() { Close(); }

bool CsvFile::Open(const std::string& path, const std::string& header, std::string* error,
                   bool flush_each_row) {
  Close();
  flush_each_row_ = flush_each_row;
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

bool CsvFile::OpenToAppend(const std::string& path, std::string* error) {
  Close();
  flush_each_row_ = true;
  file_ = std::fopen(path.c_str(), "a");
  if (file_ == nullptr) {
    *error = "cannot append to " + path + ": " + std::strerror(errno);
    return false;
  }
  return true;
}

bool CsvFile::Append(const std::string& row) {
  if (file_ == nullptr) return false;
  const bool ok = std::fputs(row.c_str(), file_) >= 0 && std::fputc('\n', file_) != EOF;
  if (!flush_each_row_) return ok;
  return std::fflush(file_) == 0 && ok;
}

bool CsvFile::Close() {
  if (file_ == nullptr) return true;
  const bool ok = std::fclose(file_) == 0;
  file_ = nullptr;
  return ok;
}

Recorder::Recorder(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh),
      private_nh_(private_nh),
      bad_position_warning_(kWarnPeriodS),
      bad_status_warning_(kWarnPeriodS),
      bad_mission_warning_(kWarnPeriodS),
      tick_warning_(kWarnPeriodS) {}

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
  // Started before on this master for this run directory, which has files: a restart.
  restarted_ = WasStartedBefore(private_nh_, run_dir_) && fs::exists(dir / "missions.csv", ec);
  if (restarted_) return OpenFilesAgain(error);
  if (!swarm_csv_.Open(run_dir_ + "/swarm_count.csv", RunMetrics::kSwarmHeader, error) ||
      !missions_csv_.Open(run_dir_ + "/missions.csv", RunMetrics::kMissionsHeader, error)) {
    return false;
  }
  WriteRun();  // the header and a row of zeros, replaced as the run goes on
  return true;
}

bool Recorder::Initialize() {
  std::string error;
  bool ok = LoadParams(&error);
  if (ok) {
    metrics_.emplace(RunMetricsParamsOf(params_),
                     [](RunMetrics::Level level, const std::string& text) {
                       if (level == RunMetrics::Level::kWarn) {
                         ROS_WARN("%s: %s", kNode, text.c_str());
                       } else {
                         ROS_INFO("%s: %s", kNode, text.c_str());
                       }
                     });
    ok = OpenFiles(&error);
  }
  if (!ok) {
    ROS_FATAL("%s: %s", kNode, error.c_str());
    return false;
  }
  stats_pub_ = nh_.advertise<Swarm_Stats>(names::kStats, kStatsQueue);
  // Small messages every tick: Nagle's algorithm would batch and delay them.
  positions_sub_ = nh_.subscribe(names::kWorldPoses, kPositionsQueue, &Recorder::OnPositions, this,
                                 ros::TransportHints().tcpNoDelay());
  mission_new_sub_ =
      nh_.subscribe(names::kMissionNew, kMissionQueue, &Recorder::OnMissionNew, this);
  status_sub_ = nh_.subscribe(names::kMissionStatus, kMissionQueue, &Recorder::OnStatus, this,
                              ros::TransportHints().tcpNoDelay());
  if (restarted_) RequestResends();
  ROS_INFO(
      "%s: local range %.3f m, sample every %.3f s of sim time, seed %lld, %s", kNode,
      params_.swarm.flocking.local_range_m, params_.sample_period_s,
      static_cast<long long>(params_.seed),
      run_dir_.empty() ? "no files (~output_dir is empty)" : ("writing to " + run_dir_).c_str());
  return true;
}

void Recorder::Run() {
  ros::CallbackQueue* queue = ros::getGlobalCallbackQueue();
  NodeDiagnostics diagnostics(nh_, "swarm_transport: recorder");
  while (ros::ok() && stop_requested_ == 0) {
    queue->callAvailable(ros::WallDuration(kSpinS));
    diagnostics.PublishIfDue([this](NodeStatus* s) {
      const std::uint64_t tick = metrics_ ? metrics_->newest_tick() : 0;
      s->message = "recording, tick " + std::to_string(tick);
      s->Add("newest_tick", tick);
      s->Add("samples", static_cast<std::uint64_t>(metrics_ ? metrics_->samples() : 0));
      s->Add("missions_done", static_cast<std::uint64_t>(metrics_ ? metrics_->missions_done() : 0));
      s->Add("missions_aborted",
             static_cast<std::uint64_t>(metrics_ ? metrics_->missions_aborted() : 0));
      s->Add("output", run_dir_.empty() ? "none" : run_dir_);
    });
  }
}

void Recorder::Shutdown() {
  if (shut_down_) return;
  shut_down_ = true;
  ForgetInstance(private_nh_);
  positions_sub_.shutdown();
  mission_new_sub_.shutdown();
  status_sub_.shutdown();
  resent_sub_.shutdown();
  request_timer_.stop();
  stats_pub_.shutdown();
  if (!metrics_) return;  // never initialized
  metrics_->Drain();
  WriteMissions(false);
  WriteRun();
  swarm_csv_.Close();
  missions_csv_.Close();
  ROS_INFO("%s: %zu samples up to tick %llu, %zu missions done, %zu aborted, %zu unfinished%s%s",
           kNode, metrics_->samples(), static_cast<unsigned long long>(metrics_->newest_tick()),
           metrics_->missions_done(), metrics_->missions_aborted(), metrics_->missions_unfinished(),
           run_dir_.empty() ? "" : "; files in ", run_dir_.c_str());
}

void Recorder::OnPositions(const Robot_Positions::ConstPtr& msg) {
  if (!std::isfinite(msg->sim_time)) {
    if (bad_position_warning_.Due()) {
      ROS_WARN("%s: ignored /flock/world_poses of tick %llu: sim_time is not finite", kNode,
               static_cast<unsigned long long>(msg->tick));
    }
    return;
  }
  const bool has_frames = metrics_->has_frames();
  const std::uint64_t newest = metrics_->newest_tick();
  if (has_frames && msg->tick <= newest) {
    // The latched message again (a reconnection), or a restarted simulator.
    if (msg->tick < newest && tick_warning_.Due()) {
      ROS_WARN(
          "%s: /flock/world_poses went back from tick %llu to %llu; ignored until it passes "
          "tick %llu again",
          kNode, static_cast<unsigned long long>(newest),
          static_cast<unsigned long long>(msg->tick), static_cast<unsigned long long>(newest));
    }
    return;
  }
  if (has_frames && msg->tick > newest + 1 && tick_warning_.Due()) {
    ROS_WARN("%s: missed /flock/world_poses ticks %llu..%llu (queue overflow or late start)", kNode,
             static_cast<unsigned long long>(newest + 1),
             static_cast<unsigned long long>(msg->tick - 1));
  }
  // Physical robots with finite positions, ascending ids, the first of duplicate ids.
  std::size_t bad = 0;
  core::MetricsFrame frame = RecorderFrame(*msg, &bad);
  frame.wall_s = ros::WallTime::now().toSec();
  if (bad > 0 && bad_position_warning_.Due()) {
    ROS_WARN("%s: ignored %zu robots with non-finite positions at tick %llu", kNode, bad,
             static_cast<unsigned long long>(msg->tick));
  }
  if (gap_open_) EndGap(msg->tick);
  std::optional<core::SwarmSample> sample;
  metrics_->AddFrame(std::move(frame), &sample);
  if (sample) Publish(*sample);
  WriteMissions(true);
}

void Recorder::Publish(const core::SwarmSample& sample) {
  Swarm_Stats stats;
  stats.tick = sample.tick;
  stats.sim_time = sample.sim_time_s;
  stats.robots = Clamp16(sample.robots);
  stats.swarm_count = Clamp16(sample.swarm_count);
  stats.largest_swarm = Clamp16(sample.largest_swarm);
  stats.live_missions = Clamp16(sample.live_missions);
  stats_pub_.publish(stats);
  if (swarm_csv_.is_open()) swarm_csv_.Append(RunMetrics::SwarmRow(sample));
}

void Recorder::OnMissionNew(const New_Mission::ConstPtr& msg) {
  const std::string warning = RecordOrder(*msg, params_.swarm, &*metrics_);
  if (!warning.empty() && bad_mission_warning_.Due()) {
    ROS_WARN("%s: %s", kNode, warning.c_str());
  }
  WriteMissions(true);
}

void Recorder::OnStatus(const Mission_Status::ConstPtr& msg) {
  const bool bad =
      msg->state > Mission_Status::REJECTED || !std::isfinite(msg->object_position_x) ||
      !std::isfinite(msg->object_position_y) || !std::isfinite(msg->distance_to_target);
  const std::string warning = RecordStatus(*msg, &*metrics_);
  // A bad status and a status of a mission not followed warn apart.
  if (!warning.empty() && (bad ? bad_status_warning_ : bad_mission_warning_).Due()) {
    ROS_WARN("%s: %s", kNode, warning.c_str());
  }
  WriteMissions(true);
}

void Recorder::WriteMissions(bool run) {
  const std::vector<std::string> rows = metrics_->TakeMissionRows();
  for (const std::string& row : rows) {
    if (missions_csv_.is_open() && !missions_csv_.Append(row)) {
      ROS_ERROR("%s: could not write a row of %s/missions.csv", kNode, run_dir_.c_str());
    }
  }
  if (run && !rows.empty()) WriteRun();
}

void Recorder::WriteRun() {
  if (run_dir_.empty()) return;
  std::string error;
  if (!WriteRunFile(run_dir_, metrics_->RunRow(params_.run_name, params_.seed), &error)) {
    ROS_ERROR("%s: %s", kNode, error.c_str());
  }
}

}  // namespace swarm_transport
