// The dispatcher's bookkeeping, pure [SPEC 6, issue 10 item 3]: which missions are accepted and
// why others are refused, their ids (chosen, reused), their phases as their first leaders
// report them, when LOADED / UNLOADED are due, and the status table. The dispatcher node only
// moves bytes between ROS and this class; the batch engine uses it for its dispatcher's part.
// Times are seconds of the caller's clock (ros::Time: simulated in lock-step), only shown.
#ifndef SWARM_TRANSPORT_CORE_MISSION_BOOK_H_
#define SWARM_TRANSPORT_CORE_MISSION_BOOK_H_

#include <array>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_message.h"

namespace swarm_transport {
namespace core {

struct MissionBookParams {
  double world_size_m = 11.088889;
  double tick_period_s = 0.1;
  double loaded_delay_s = 2.0;    // LOADED this long after LOADING; < 0: only on a signal
  double unloaded_delay_s = 2.0;  // UNLOADED this long after UNLOADING; < 0: only on a signal
  int max_live_missions = 64;     // more are refused
  // A running mission (GATHERING .. UNLOADING) whose first leader said nothing (no phase, no
  // progress report) for this long is silent: its first leader is lost (< 0: never).
  double silent_after_s = -1.0;
  std::vector<Zone> static_zones;  // a transport must have a route around them (SPEC 9.8)
};

// What a first leader reports (phase status / progress), already checked for finite fields.
struct MissionReport {
  std::uint16_t mission_id = 0;
  MissionPhase phase = MissionPhase::kQueued;
  std::string reason;
  std::uint64_t tick = 0;  // 0: unknown (the dispatcher's own reports)
  std::uint16_t robots_assigned = 0;
  std::uint16_t robots_inside = 0;
  double distance_to_target_m = 0.0;
};

// One line for logs and verdicts: robots, leaders, object, target, mode.
std::string DescribeMission(const MissionSpec& mission);

class MissionBook {
 public:
  // Completed missions kept for the table; older ones are forgotten first.
  static constexpr std::size_t kMaxFinishedMissions = 1000;

  // What the book knows about one mission.
  struct Entry {
    MissionSpec spec;
    bool has_spec = false;  // false for a mission first seen through a status
    std::string source;     // service | missions_file | topic | status (order never heard)
    MissionPhase phase = MissionPhase::kQueued;
    std::string reason;
    std::uint16_t robots_assigned = 0;
    std::uint16_t robots_inside = 0;
    double distance_to_target_m = 0.0;
    std::array<double, 8> entered{};  // when each phase was first entered (caller's seconds)
    std::uint8_t reached = 0;         // bit p: phase p was entered
    bool loaded_sent = false;
    bool unloaded_sent = false;
    // The LOADED / UNLOADED of its phase as last sent: when (caller's seconds) and its tick
    // (Owed sends the same again).
    double signal_s = 0.0;
    std::uint64_t signal_tick = 0;
    std::uint64_t generation = 0;  // tells a reused id's new entry from the forgotten one
    std::uint64_t phase_tick = 0;  // the first leader's tick of its latest report
    double heard_s = 0.0;          // when its first leader (or its order) was last heard of
    bool Live() const;
  };

  // The answer to a submission.
  struct Verdict {
    bool accepted = false;
    bool attached = false;  // an order for a mission first seen through its status
    std::uint16_t id = 0;
    std::string reason;   // why refused
    std::string message;  // the sentence for the submitter
    MissionSpec spec;     // as accepted (its id chosen) or refused
  };

  explicit MissionBook(MissionBookParams params) : params_(params) {}

  // Validates `spec` (arena, `known_robots` when not empty, live ids, the live limit) and, when
  // accepted, follows it as QUEUED from `now_s`. id 0 with `auto_id` takes the next free id (a
  // refused mission does not use one up). `attach`: an order for a live mission first seen
  // through its status is attached to it instead of refused as a duplicate (a raw order heard
  // on the topic; a submission always names a new mission).
  Verdict Submit(MissionSpec spec, const std::string& source, bool auto_id, bool attach,
                 const std::set<std::uint16_t>& known_robots, double now_s);

  // What a first leader's phase report did.
  struct StatusOutcome {
    std::vector<core::Signal> signals;  // due now: LOADED after LOADING, UNLOADED after UNLOADING
    bool entered = false;               // the mission entered the reported phase
    bool followed = false;              // first seen through this report (its order never heard)
    std::string ignored;                // why it changed nothing, when it did not
  };
  // A first leader's phase report: each signal is due once, with the configured delay stamped
  // as a tick (SignalTick). Ignored: a finished mission's late news, a REJECTED from elsewhere,
  // a new mission beyond the live limit.
  StatusOutcome OnStatus(const MissionReport& report, double now_s);
  // A first leader's latest status of a mission, re-sent on request after the dispatcher
  // (re)started (docs/reliability.md), with the order the robot still carries (`order`, may be
  // null). A mission not tracked is followed from it as OnStatus does (source "resent", the
  // LOADED / UNLOADED its phase makes due included) and gets the order; a tracked one without
  // an order gets it; a status of an earlier phase than the book's changes nothing. Every id
  // re-sent moves the next automatic id above it: new orders do not take the id of a mission
  // that ran before the restart.
  StatusOutcome Restore(const MissionReport& report, const MissionSpec* order, double now_s);
  // A report within a phase: robots inside, distance to go (and its first leader is alive).
  void OnProgress(const MissionReport& report, double now_s);
  // A user's LOADED / UNLOADED for a live mission (takes effect at once), sent at `now_s`.
  // Empty when it is to be sent, else why not.
  std::string Signal(std::uint16_t mission_id, MissionEventKind kind, double now_s);

  // The LOADED / UNLOADED sent at least `after_s` before `now_s` (and not again since) of the
  // missions still in the phase it was sent for: due again, stamped with the same tick (a robot
  // takes a repeat as the same signal). A real-time event is not latched: a robot not yet
  // connected to a restarted dispatcher misses it, and its mission stood in UNLOADING for good
  // (issue 29).
  std::vector<core::Signal> Owed(double now_s, double after_s);
  // Running missions whose first leader has been silent for silent_after_s at `now_s`, with
  // the reason to end them for (naming the first leader and the last word heard).
  std::vector<std::pair<std::uint16_t, std::string>> Silent(double now_s) const;
  // Ends a live mission as ABORTED with `reason` (the dispatcher's own decision). False when
  // it is not live.
  bool Abort(std::uint16_t mission_id, const std::string& reason, double now_s);

  // The status table: one line per mission, seconds per phase up to `now_s`.
  std::string Table(double now_s) const;
  int LiveCount() const;
  const Entry* Find(std::uint16_t id) const;
  const std::map<std::uint16_t, Entry>& entries() const { return entries_; }
  // Arena, known robots and live ids for a validation (`ignore_id` not counted as live).
  MissionContext Context(const std::set<std::uint16_t>& known_robots, int ignore_id = -1) const;

  // An id no tracked mission has, taken (the next call gives another): a recruiting order's
  // id before it is submitted (SPEC 9.4).
  std::uint16_t NextFreeId();

 private:
  void EnterPhase(std::uint16_t id, Entry* entry, MissionPhase phase, double now_s,
                  std::vector<core::Signal>* signals);
  void Forget();

  MissionBookParams params_;
  std::map<std::uint16_t, Entry> entries_;
  // Finished missions in the order they finished: (id, generation).
  std::deque<std::pair<std::uint16_t, std::uint64_t>> finished_;
  std::uint64_t next_generation_ = 1;
  std::uint16_t next_id_ = 1;
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_MISSION_BOOK_H_
