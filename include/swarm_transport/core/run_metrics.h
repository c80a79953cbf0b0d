// The recorder's bookkeeping, pure [SPEC 8, issue 10 item 3]: swarm samples on a sim-time grid,
// each mission's phases and its transport / leader metrics over its window, and the CSV rows of
// swarm_count.csv, missions.csv and run.csv. The recorder node only moves bytes between ROS and
// this class; the in-process batch runner (scripts/experiment --engine batch) feeds it the same
// frames and statuses, so both write the same rows.
#ifndef SWARM_TRANSPORT_CORE_RUN_METRICS_H_
#define SWARM_TRANSPORT_CORE_RUN_METRICS_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/metrics.h"
#include "swarm_transport/core/mission.h"

namespace swarm_transport {
namespace core {

// The physical robots of one tick: ascending unique ids with finite positions.
struct MetricsFrame {
  std::uint64_t tick = 0;
  double sim_time_s = 0.0;
  double wall_s = 0.0;  // wall clock when it was taken (0: not known; the batch runs)
  std::vector<std::uint16_t> ids;
  std::vector<Vec2> positions;
  // Index of robot `id`, or -1.
  long IndexOf(std::uint16_t id) const;
};

// One swarm sample [T7.2]: what /flock/stats carries and swarm_count.csv holds.
struct SwarmSample {
  std::uint64_t tick = 0;
  double sim_time_s = 0.0;
  std::size_t robots = 0;
  std::size_t swarm_count = 0;
  std::size_t largest_swarm = 0;
  std::size_t live_missions = 0;
};

struct RunMetricsParams {
  double local_range_m = 0.5;     // swarms and leader contact
  double goal_tolerance_m = 0.1;  // a leader-only mission's arrival
  double sample_period_s = 10.0;  // sim time between swarm samples
  // The run row's dispersion of the last frame (SPEC 9.5): the arena, and how far around a
  // robot counts as covered (m), on cells of coverage_cell_m.
  double world_size_m = 11.088889;
  double coverage_radius_m = 1.0;
  double coverage_cell_m = 0.1;
  // > 0: frames taken (wall_s) longer ago than this before the newest also leave the history.
  // Statuses come late by wall time (messages queued), not by ticks: in real time 20,000 frames
  // are 33 minutes, and a long-lived recorder held them all (~11 MB at 25 robots).
  double history_wall_s = 0.0;
};

class RunMetrics {
 public:
  enum class Level { kInfo, kWarn };
  // Where the class reports what a recorder logs (a mission row written, a frame lacking one of
  // a mission's robots, ...); warnings of one kind come at most once per mission.
  using Log = std::function<void(Level, const std::string&)>;

  static const char kSwarmHeader[];
  static const char kMissionsHeader[];
  static const char kRunHeader[];

  // Frames kept for missions whose status arrives late: as many as hold kHistoryPositions
  // robot positions, within [kMinHistoryFrames, kMaxHistoryFrames] (and no older than
  // RunMetricsParams::history_wall_s).
  static constexpr std::size_t kHistoryPositions = 4000000;
  static constexpr std::size_t kMinHistoryFrames = 256;
  static constexpr std::size_t kMaxHistoryFrames = 20000;
  static std::size_t HistoryCapacity(std::size_t robots);
  // Missions followed at once; more are ignored (AddOrder / AddStatus say why).
  static constexpr std::size_t kMaxMissions = 4096;

  explicit RunMetrics(RunMetricsParams params, Log log = Log());

  // The newest frame; its tick must be above the last frame's (else false, nothing changes).
  // Returns the sample when its sample time has come.
  bool AddFrame(MetricsFrame frame, std::optional<SwarmSample>* sample);
  // A valid order (the caller validated it), known from tick max(newest frame, start_tick).
  // Empty when followed, else why not.
  std::string AddOrder(const MissionSpec& spec, std::uint64_t start_tick);
  // A first leader's status (phase <= kRejected, finite object). Empty when taken, else why not.
  std::string AddStatus(std::uint16_t mission_id, MissionPhase phase, std::uint64_t tick,
                        Vec2 object);
  // The run is over: every mission gets the frames it has, finished ones are written.
  void Drain();

  // A restarted recorder (docs/reliability.md, run_metrics_resume.cpp). `id`'s row was written
  // by an earlier recorder of this run: a re-sent status of it is not written again.
  void MarkRowWritten(std::uint16_t id) { rows_of_.insert(id); }
  // Counts of the earlier recorders of this run, added to run.csv's.
  void Carry(std::size_t samples, double swarm_count_sum, std::size_t done, std::size_t aborted);
  // A first leader's latest status of a mission (phase <= kRejected, finite object) re-sent on
  // request, with the order it carries (may be null). A mission with a row in this run's
  // missions.csv changes nothing (no row twice); one not followed is followed from it as
  // recovered (its row follows a comment line saying so: the phases before the status have
  // no ticks): a mission that ended while no recorder ran gets its row at once, a running one
  // when it ends. Empty when taken, else why not.
  std::string AddResent(const MissionSpec* order, std::uint16_t mission_id, MissionPhase phase,
                        std::uint64_t tick, Vec2 object);

  // missions.csv rows (no newline) of the missions finished since the last call, in the order
  // they were written.
  std::vector<std::string> TakeMissionRows();
  // The swarm_count.csv row of a sample.
  static std::string SwarmRow(const SwarmSample& sample);
  // The run.csv row so far.
  std::string RunRow(const std::string& run_name, std::int64_t seed) const;

  std::size_t samples() const { return samples_; }
  std::size_t missions_done() const { return missions_done_; }
  std::size_t missions_aborted() const { return missions_aborted_; }
  std::size_t missions_unfinished() const;
  // Tick of the newest frame (0 without frames).
  std::uint64_t newest_tick() const { return history_.empty() ? 0 : history_.back().tick; }
  bool has_frames() const { return !history_.empty(); }

 private:
  struct MissionRecord {
    MissionSpec spec;
    bool has_spec = false;
    std::optional<std::uint64_t> known_tick;              // its order arrived
    std::array<std::optional<std::uint64_t>, 8> entered;  // first tick of each phase
    std::optional<std::uint64_t> arrival_tick;  // leader-only: leader seen within tolerance
    std::optional<MissionPhase> final_state;    // DONE or ABORTED once reported
    std::optional<Vec2> object;                 // last reported object centre
    std::optional<std::uint64_t> fed_through;   // last frame fed to the trackers
    TransportTracker transport;
    // Transport: the nearest-neighbour spacing CV of its robots at the transport's first frame.
    std::optional<double> loading_nn_cv;
    std::optional<LeaderTracker> leader;
    bool warned_missing = false;
    bool warned_history = false;
    bool recovered = false;  // first known from a re-sent status (AddResent)
  };

  std::optional<SwarmSample> SampleIfDue(const MetricsFrame& frame);
  static std::optional<std::uint64_t> WindowStart(const MissionRecord& m);
  static std::optional<std::uint64_t> WindowEnd(const MissionRecord& m);
  void FeedMissions(bool drain, std::optional<std::uint64_t> through = std::nullopt);
  void Feed(std::uint16_t id, MissionRecord* m, const MetricsFrame& frame);
  void WriteFinished(bool drain);
  std::string MissionRow(std::uint16_t id, const MissionRecord& m) const;
  // The comment line before a recovered mission's row.
  static std::string RecoveredComment(std::uint16_t id);
  void Say(Level level, const std::string& text) const;

  RunMetricsParams params_;
  Log log_;
  std::deque<MetricsFrame> history_;  // newest at the back
  std::map<std::uint16_t, MissionRecord> missions_;
  std::set<std::uint16_t> written_;  // ids of rows written; late news of them is ignored
  // Ids of every row of this run's missions.csv, an earlier recorder's included (AddResent).
  std::set<std::uint16_t> rows_of_;
  std::vector<std::string> rows_;  // written, not taken yet
  std::optional<double> first_sample_time_s_;
  double next_sample_time_s_ = 0.0;
  std::size_t samples_ = 0;
  double swarm_count_sum_ = 0.0;
  std::size_t missions_done_ = 0;
  std::size_t missions_aborted_ = 0;
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_RUN_METRICS_H_
