// The mission dispatcher's policy, pure [SPEC 6, 9.4, 9.10]: what it accepts and refuses
// (the verdicts of its MissionBook), the robots it picks for a count-only order, the recruiting
// missions and their statists, when the missions file enters a run, the LOADED / UNLOADED it
// sends and the missions it ends for a silent first leader. It knows the swarm of the latest
// positions it was given and says what to do through a DispatcherOutlet; the dispatcher node
// and the batch runs only convert and carry it out.
#ifndef SWARM_TRANSPORT_CORE_DISPATCHER_POLICY_H_
#define SWARM_TRANSPORT_CORE_DISPATCHER_POLICY_H_

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/core/assignment.h"
#include "swarm_transport/core/dispatcher_answer.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/core/recruit.h"

namespace swarm_transport {
namespace core {

// A recruit's statist id: this minus its slot (0 .. kMaxRecruiting - 1).
constexpr std::uint16_t kRecruitStatistId = 65535;

struct DispatcherPolicyParams {
  MissionBookParams book;
  SelectionParams selection;  // count-only picking (SPEC 9.10)
  // Lock-step (the simulator's clock): file missions and recruits' orders are stamped with the
  // tick they enter, and every positions and status taken is answered with a DispatcherAnswer
  // (core/dispatcher_answer.h); else they go when due.
  bool lockstep = false;
  double start_delay_s = 1.0;  // file missions without at_tick: this long after the first swarm
  // Real time: the watchdog sends a LOADED / UNLOADED again when its mission is still in the
  // phase it was sent for this long after (MissionBook::Owed; <= 0: never).
  double signal_resend_s = 5.0;
  // Lock-step: the robots at tick `tick` given those of now (a scenario's spawns and kills);
  // empty: those of now.
  std::function<std::set<std::uint16_t>(const std::set<std::uint16_t>&, std::uint64_t)> robots_at;
  // The run's clock in seconds (ros::Time: simulated in lock-step): the book's times.
  std::function<double()> clock = [] { return 0.0; };
};

// What the policy does: carried out by its owner, in the order of the calls.
class DispatcherOutlet {
 public:
  virtual ~DispatcherOutlet() = default;
  // An accepted order goes out, stamped with `start_tick` (lock-step; 0: when it arrives).
  virtual void Order(const MissionSpec& spec, std::uint64_t start_tick) = 0;
  // A refused mission's REJECTED status with `reason`.
  virtual void Rejected(const MissionSpec& spec, const std::string& reason) = 0;
  // A mission ended as ABORTED (its first leader is silent): its status and its object's delete.
  virtual void Aborted(const MissionSpec& spec, const std::string& reason) = 0;
  // A LOADED / UNLOADED, `why` for the log.
  virtual void Event(const Signal& signal, const char* why) = 0;
  // Real time: a recruit's statist stands (or is gone), stacked `copies` times.
  virtual void StatistUp(std::uint16_t /*statist_id*/, Vec2 /*at*/, int /*copies*/) {}
  virtual void StatistDown(std::uint16_t /*statist_id*/, int /*copies*/) {}
  // Lock-step: an answer to the simulator's barrier.
  virtual void Answer(const DispatcherAnswer& /*answer*/) {}
  virtual void Log(bool warn, const std::string& text) = 0;
};

class DispatcherPolicy {
 public:
  // At most this many missions recruit at once: each has a statist of its own.
  static constexpr std::size_t kMaxRecruiting = 256;
  // A recruit's statist counts this many times in every centroid (stacked copies, thesis
  // 5.5.3): one would weigh as little as one robot of a neighbourhood.
  static constexpr int kRecruitStatistCopies = 3;

  // `outlet` must outlive the policy.
  DispatcherPolicy(DispatcherPolicyParams params, DispatcherOutlet* outlet);

  // The missions file with each mission's at_tick (0: start_delay_s).
  void SetFileMissions(std::vector<MissionSpec> missions, std::vector<std::uint64_t> at_ticks);

  // A submission (service, file, a raw order heard on the topic): a count-only order gets its
  // robots picked (PickRobotsByCount), a recruiting one starts recruiting, the others are
  // validated by the book against the swarm known now. `publish`: its order goes out (else it
  // is on the topic already and may attach to a mission first seen through its status). id 0
  // with `auto_id` picks the next free id. Refused: a REJECTED status, nothing else changes.
  MissionBook::Verdict Submit(MissionSpec spec, const std::string& source, bool auto_id,
                              bool publish, std::uint64_t start_tick = 0);

  // The physical robots of a new positions message of tick `tick` (by id). Lock-step: the
  // first schedules the missions file at its stamped ticks; every one is watched by the
  // recruits and answered. Real time: the first submits the file missions due now and returns the
  // later groups (at_tick, delay s) for the caller to submit with SubmitFileMissions when due.
  std::vector<std::pair<std::uint64_t, double>> OnSwarm(
      std::uint64_t tick, std::map<std::uint16_t, PlannerRobot> robots);
  // Only the swarm, nothing else (a driver that schedules nothing).
  void SetSwarm(std::uint64_t tick, std::map<std::uint16_t, PlannerRobot> robots);
  // Real time: the file missions of this at_tick (0: those of start_delay_s).
  void SubmitFileMissions(std::uint64_t at_tick);
  // Real time: the robots whose own process is not connected to the orders now (killed, or
  // started again and not connected yet). Their bodies may still stand in the world and be
  // heard, but an order would not reach them: robot_count and recruiting pick none of them (a
  // member that never got its order but was heard held its mission's GATHERING for good).
  void SetUnreachable(std::set<std::uint16_t> robots) { unreachable_ = std::move(robots); }

  // A first leader's phase report (its fields checked) from `from`: the LOADED / UNLOADED now
  // due go out (lock-step: and an answer naming the status and them).
  MissionBook::StatusOutcome OnStatus(const MissionReport& report, const std::string& from);
  // A first leader's latest status re-sent on request after a restart, with the order it
  // carries (may be null), from `from` (MissionBook::Restore): the LOADED / UNLOADED it makes
  // due go out. Not answered in lock-step: a re-sent status is not relayed.
  MissionBook::StatusOutcome OnResent(const MissionReport& report, const MissionSpec* order,
                                      const std::string& from);
  // Lock-step: a status taken but not booked (a bad or foreign one) is answered all the same.
  void SkipStatus(const StatusKey& status);
  void OnProgress(const MissionReport& report) { book_.OnProgress(report, params_.clock()); }
  // A user's LOADED / UNLOADED: sent (empty) or why not.
  std::string Signal(std::uint16_t mission_id, MissionEventKind kind);
  // Ends the missions whose first leader is silent by the run's clock and still is after
  // `grace_s` of wall time (`wall_s`: now; a fast lock-step passes many ticks in little wall
  // time, while their statuses may wait in a queue).
  void Watchdog(double wall_s, double grace_s);
  // The status table, and the tick of the swarm it picks robots from.
  std::string Table() const;

  const MissionBook& book() const { return book_; }
  bool has_swarm() const { return has_swarm_; }
  std::uint64_t swarm_tick() const { return swarm_tick_; }
  std::size_t file_mission_count() const { return file_missions_.size(); }

 private:
  struct Recruiting {
    MissionSpec spec;
    RecruitWatch watch;
    std::string source;
    std::uint64_t start_tick = 0;  // lock-step: its statist stands from this tick
    std::uint16_t statist_id = 0;
  };

  MissionBook::Verdict Submit(MissionSpec spec, const std::string& source, bool auto_id,
                              bool publish, std::uint64_t start_tick,
                              const std::set<std::uint16_t>& robots);
  MissionBook::Verdict Refuse(MissionSpec spec, const std::string& source, const std::string& why);
  MissionBook::Verdict StartRecruit(MissionSpec spec, const std::string& source, bool auto_id,
                                    std::uint64_t start_tick);
  // Lock-step: the orders they send (id, start tick).
  std::vector<std::pair<std::uint16_t, std::uint64_t>> WatchRecruits();
  std::vector<std::pair<std::uint16_t, std::uint64_t>> ScheduleFileMissions();
  // Lock-step: the answer with what was sent since the last one.
  void SendAnswer(std::vector<std::pair<std::uint16_t, std::uint64_t>> orders,
                  std::vector<core::Signal> events = {},
                  std::optional<StatusKey> status = std::nullopt);
  std::set<std::uint16_t> KnownRobots() const;
  std::map<std::uint16_t, PlannerRobot> IdleRobots() const;
  void Log(bool warn, const char* format, ...);

  DispatcherPolicyParams params_;
  DispatcherOutlet* outlet_;
  MissionBook book_;
  std::map<std::uint16_t, PlannerRobot> swarm_;
  std::uint64_t swarm_tick_ = 0;
  bool has_swarm_ = false;
  std::vector<MissionSpec> file_missions_;
  std::vector<std::uint64_t> file_ticks_;
  bool file_missions_scheduled_ = false;
  std::map<std::uint16_t, Recruiting> recruiting_;
  std::map<std::uint16_t, double> silent_since_;  // silent missions: since when (wall s)
  std::set<std::uint16_t> unreachable_;           // SetUnreachable
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_DISPATCHER_POLICY_H_
