// The recorder node [SPEC 8]: swarm counts, transport and leader metrics per mission, CSV files.
#ifndef SWARM_TRANSPORT_ROS_RECORDER_H_
#define SWARM_TRANSPORT_ROS_RECORDER_H_

#include <ros/ros.h>

#include <array>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/New_Mission.h"
#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/core/metrics.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/ros/params.h"

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

// An append-only CSV file: header at open, every row flushed at once so that the file is
// complete up to the last row even when the process is killed.
class CsvFile {
 public:
  CsvFile() = default;
  ~CsvFile();
  CsvFile(const CsvFile&) = delete;
  CsvFile& operator=(const CsvFile&) = delete;
  // Truncates `path` and writes `header`. False with `error` when it cannot.
  bool Open(const std::string& path, const std::string& header, std::string* error);
  bool is_open() const { return file_ != nullptr; }
  // Appends one line (without its newline) and flushes; false on a write error.
  bool Append(const std::string& row);
  void Close();

 private:
  std::FILE* file_ = nullptr;
};

// Subscribes /flock/positions (every tick), /flock/mission/new and /flock/mission/status;
// publishes /flock/stats at every sample; writes swarm_count.csv (one row per sample),
// missions.csv (one row per DONE / ABORTED mission) and run.csv (one summary row, rewritten
// after every finished mission and at shutdown) to <output_dir>/<run_name>/.
// Mission phases come from the first leader's Mission_Status ticks; a mission's metrics are
// fed from buffered /flock/positions frames inside its window once the window's end is known,
// or a frame when it leaves the history (HistoryCapacity frames), so a status that arrives
// after later frames still cuts the window at its own tick (in lock-step at thousands of
// ticks per second, hundreds of frames may come first). A transport's window is
// TRANSPORT .. UNLOADING. A
// leader-only mission's runs from its order (the leader leads as soon as it holds it; its
// first status may come much later, see RobotNode::MissionOutletsReady) to its DONE, or to
// the first tick the leader is within goal_tolerance_m of the target - the leader's own
// arrival test, which also stands for a DONE that was lost. Single-threaded (Run() spins
// the global queue).
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

  // Frames kept for missions whose status arrives late: as many as hold kHistoryPositions
  // robot positions, within [kMinHistoryFrames, kMaxHistoryFrames].
  static constexpr std::size_t kHistoryPositions = 4000000;
  static constexpr std::size_t kMinHistoryFrames = 256;
  static constexpr std::size_t kMaxHistoryFrames = 20000;
  static std::size_t HistoryCapacity(std::size_t robots);
  // Missions followed at once; more are ignored with a warning.
  static constexpr std::size_t kMaxMissions = 4096;

 private:
  // One /flock/positions message: physical robots with finite positions, ascending ids.
  struct Frame {
    std::uint64_t tick = 0;
    double sim_time_s = 0.0;
    std::vector<std::uint16_t> ids;
    std::vector<core::Vec2> positions;
    // Index of robot `id`, or -1.
    long IndexOf(std::uint16_t id) const;
  };
  // What the recorder knows of one mission.
  struct MissionRecord {
    core::MissionSpec spec;
    bool has_spec = false;
    std::optional<std::uint64_t> known_tick;              // its New_Mission arrived
    std::array<std::optional<std::uint64_t>, 8> entered;  // first tick of each phase
    std::optional<std::uint64_t> arrival_tick;      // leader-only: leader seen within tolerance
    std::optional<core::MissionPhase> final_state;  // DONE or ABORTED once reported
    std::optional<core::Vec2> object;               // last reported object centre
    std::optional<std::uint64_t> fed_through;       // last frame fed to the trackers
    core::TransportTracker transport;
    std::optional<core::LeaderTracker> leader;
    bool warned_missing = false;  // a frame lacked one of its robots
    bool warned_history = false;  // its window began before the oldest kept frame
  };

  bool LoadParams(std::string* error);
  bool OpenFiles(std::string* error);

  void OnPositions(const Robot_Positions::ConstPtr& msg);
  void OnMissionNew(const New_Mission::ConstPtr& msg);
  void OnStatus(const Mission_Status::ConstPtr& msg);

  // Samples the newest frame when its sample time has come.
  void SampleIfDue(const Frame& frame);
  // The window (start, end] of frames that feed the mission's metrics.
  static std::optional<std::uint64_t> WindowStart(const MissionRecord& m);
  static std::optional<std::uint64_t> WindowEnd(const MissionRecord& m);
  // Feeds every mission the buffered frames it is due: all of them when its window's end is
  // known or `drain` (shutdown), else those up to tick `through` (a frame leaving the
  // history), else none.
  void FeedMissions(bool drain, std::optional<std::uint64_t> through = std::nullopt);
  void Feed(MissionRecord* m, const Frame& frame);
  // Writes and forgets finished missions whose frames are all in; `drain`: all of them.
  void WriteFinished(bool drain);
  void WriteMission(std::uint16_t id, const MissionRecord& m);
  void WriteRun();
  // True at most once per warning period (wall clock) for one kind of warning.
  static bool WarnDue(ros::WallTime* last);

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

  std::deque<Frame> history_;  // newest at the back
  std::map<std::uint16_t, MissionRecord> missions_;
  std::set<std::uint16_t> written_;  // ids of rows written; late news of them is ignored
  std::optional<double> first_sample_time_s_;
  double next_sample_time_s_ = 0.0;
  std::size_t samples_ = 0;
  double swarm_count_sum_ = 0.0;
  std::size_t missions_done_ = 0;
  std::size_t missions_aborted_ = 0;
  ros::WallTime last_bad_position_warning_;
  ros::WallTime last_bad_status_warning_;
  ros::WallTime last_bad_mission_warning_;
  ros::WallTime last_tick_warning_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_RECORDER_H_
