// The recorder node [SPEC 8]: swarm counts, transport and leader metrics per mission, CSV files.
#ifndef SWARM_TRANSPORT_ROS_RECORDER_H_
#define SWARM_TRANSPORT_ROS_RECORDER_H_

#include <ros/ros.h>

#include <csignal>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>

#include "swarm_transport/Mission_Resent.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/New_Mission.h"
#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/core/mission_agent.h"
#include "swarm_transport/core/run_metrics.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/common/wall_throttle.h"

namespace swarm_transport {

// Everything the recorder is configured with, units in the names.
struct RecorderParams {
  SwarmConfig swarm;              // /swarm: local_range_m, goal_tolerance_m, world_size_m
  std::string output_dir;         // ~output_dir: "" = write no files, only publish /flock/stats
  std::string run_name = "run";   // ~run_name: files go to <output_dir>/<run_name>/
  double sample_period_s = 10.0;  // ~sample_period_s: sim time between swarm samples [T7.2]
  std::int64_t seed = 0;          // ~seed (default /swarm/seed): written into run.csv

  // Empty when valid, else one sentence naming the bad parameter.
  std::string Validate() const;
};

// The recorder's bookkeeping parameters (core::RunMetrics) of `params`.
core::RunMetricsParams RunMetricsParamsOf(const RecorderParams& params);

// An append-only CSV file: header at open, every row flushed at once so that the file is
// complete up to the last row even when the process is killed (unless opened without: a
// trace of every robot at every tick is written at the close).
class CsvFile {
 public:
  CsvFile() = default;
  ~CsvFile();
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;
  // Truncates `path` and writes `header`. False with `error` when it cannot.
  bool Open(const std::string& path, const std::string& header, std::string* error,
            bool flush_each_row = true);
  // Opens `path` to append rows after what it holds (a restarted recorder's), flushing each.
  bool OpenToAppend(const std::string& path, std::string* error);
  bool is_open() const { return file_ != nullptr; }
  // Appends one line (without its newline) and flushes; false on a write error.
  bool Append(const std::string& row);
  // False when a write failed (nothing open: true).
  bool Close();

 private:
  std::FILE* file_ = nullptr;
  bool flush_each_row_ = true;
};

// What the recorder makes of the messages it hears - the recorder node on its topics, the batch
// engine on its own run's - with the same checks. Each returns an empty string when taken, else
// the warning to give.
// /flock/world_poses -> a frame: physical robots with finite positions, ascending ids, the first of
// duplicate ids; `bad` counts those with non-finite positions.
core::MetricsFrame RecorderFrame(const Robot_Positions& msg, std::size_t* bad);
// The same of a message's fields.
core::MetricsFrame RecorderFrame(std::uint64_t tick, double sim_time,
                                 const std::vector<Robot_Position>& positions, std::size_t* bad);
// An order (as published) is followed when valid in the arena.
std::string RecordOrder(const New_Mission& msg, const SwarmConfig& swarm,
                        core::RunMetrics* metrics);
// A phase status (state <= REJECTED, finite fields) is booked for its mission.
std::string RecordStatus(const Mission_Status& msg, core::RunMetrics* metrics);
// The same of a status report of tick `tick` (the batch runs').
std::string RecordStatus(const core::StatusReport& status, std::uint64_t tick,
                         core::RunMetrics* metrics);
// Writes <run_dir>/run.csv: the header and `row`, written aside and renamed over the old file
// so that a reader never sees half a file.
bool WriteRunFile(const std::string& run_dir, const std::string& row, std::string* error);

// Subscribes /flock/world_poses (every tick), /flock/mission/new and /flock/mission/status;
// publishes /flock/stats at every sample; writes swarm_count.csv (one row per sample),
// missions.csv (one row per DONE / ABORTED mission) and run.csv (one summary row, rewritten
// after every finished mission and at shutdown) to <output_dir>/<run_name>/.
// The bookkeeping - the sampling grid, each mission's phases, window and metrics, the rows -
// is core::RunMetrics; this node validates the messages (warning about bad ones at most once
// per warning period), turns them into frames, orders and statuses, and moves the results to
// /flock/stats and the files. Single-threaded (Run() spins the global queue).
class Recorder {
 public:
  Recorder(ros::NodeHandle nh, ros::NodeHandle private_nh);
  // Loads and validates parameters, opens the files, connects topics. False (after one
  // ROS_FATAL) on bad parameters or files that cannot be written.
  bool Initialize();
  // Spins until ROS shuts down or RequestStop() was called.
  void Run();
  // Writes the rows of finished missions still waiting for frames, the final run.csv, and
  // closes the files. Idempotent.
  void Shutdown();
  // Async-signal-safe: makes Run() return. For SIGINT / SIGTERM handlers installed instead of
  // roscpp's, whose shutdown would stop the logging of the closing summary.
  static void RequestStop();

 private:
  bool LoadParams(std::string* error);
  bool OpenFiles(std::string* error);

  // A restart on the same master (recorder_resume.cpp): appends to the run's files after a gap
  // comment, takes over the earlier recorder's rows and counts, and asks the first leaders to
  // re-send their missions' latest statuses.
  bool OpenFilesAgain(std::string* error);
  void RequestResends();
  void OnResent(const Mission_Resent::ConstPtr& msg);
  // Marks the gap's end (the first frame after a restart) in both files.
  void EndGap(std::uint64_t tick);

  void OnPositions(const Robot_Positions::ConstPtr& msg);
  void OnMissionNew(const New_Mission::ConstPtr& msg);
  void OnStatus(const Mission_Status::ConstPtr& msg);

  // Publishes /flock/stats and appends the swarm_count.csv row of a sample.
  void Publish(const core::SwarmSample& sample);
  // Appends the missions.csv rows the metrics wrote since the last call; then, when there
  // were any and `run`, rewrites run.csv.
  void WriteMissions(bool run);
  // Rewrites run.csv: written aside and renamed over the old file.
  void WriteRun();

  static volatile std::sig_atomic_t stop_requested_;

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  RecorderParams params_;
  std::string run_dir_;  // "" when no files are written
  CsvFile swarm_csv_;
  CsvFile missions_csv_;
  bool shut_down_ = false;

  ros::Publisher stats_pub_;
  ros::Subscriber positions_sub_;
  ros::Subscriber mission_new_sub_;
  ros::Subscriber status_sub_;
  bool restarted_ = false;  // ran before on this master: appends (OpenFilesAgain)
  bool gap_open_ = false;   // restarted and no frame yet
  ros::Subscriber resent_sub_;
  ros::Publisher request_pub_;
  ros::WallTimer request_timer_;
  std::uint32_t requests_ = 0;

  std::optional<core::RunMetrics> metrics_;  // made once the parameters are loaded
  // At most one warning of a kind per kWarnPeriodS of wall time (recorder.cpp).
  WarnThrottle bad_position_warning_;
  WarnThrottle bad_status_warning_;
  WarnThrottle bad_mission_warning_;
  WarnThrottle tick_warning_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_RECORDER_H_
