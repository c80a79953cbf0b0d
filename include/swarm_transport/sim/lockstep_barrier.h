// The lock-step barrier [SPEC 7]: when is a tick complete? Pure bookkeeping (no ROS, no
// clock): the simulator's adapter feeds it what arrives and asks it whether to go on.
//
// A tick is complete when every live robot asked answered it - one answer per robot and tick,
// naming the tick and carrying the command and every mission message the robot sends in it, so
// nothing else has to be counted or waited for (issue 10, item 4) - and, with a dispatcher,
// when every LOADED / UNLOADED it owes for a relayed LOADING / UNLOADING arrived (it is stamped
// with the tick at which it applies), and its scheduled orders due by then.
#ifndef SWARM_TRANSPORT_SIM_LOCKSTEP_BARRIER_H_
#define SWARM_TRANSPORT_SIM_LOCKSTEP_BARRIER_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/mission.h"

namespace swarm_transport {
namespace sim {

class LockstepBarrier {
 public:
  using EventKey = std::pair<std::uint16_t, std::uint8_t>;  // (mission id, event kind)

  // What an answer did to the barrier.
  enum class Answer {
    kAnswer,       // the answer to the current tick
    kStale,        // the late answer to an earlier tick: ignored (the robot stood in it)
    kUnsolicited,  // a tick it was not asked (a later one, or twice): ignored
    kOutside,      // the robot is not live: not the barrier's business
  };

  // Robots. A robot must be added before anything else about it counts.
  void Add(std::uint16_t id);
  void Remove(std::uint16_t id);
  bool Has(std::uint16_t id) const { return robots_.count(id) != 0; }
  bool Live(std::uint16_t id) const;
  // It is connected: from the next perception on it must answer every tick.
  void MakeLive(std::uint16_t id);
  void MakeNotLive(std::uint16_t id);
  // No robot is asked anything any more (the last tick is over).
  void EndAll();

  // A tick: `Ask` each live robot that gets a perception (after StartTick).
  void StartTick(std::uint64_t tick);
  void Ask(std::uint16_t id);
  // Robot `id`'s answer to tick `tick` with its command.
  Answer OnAnswer(std::uint16_t id, std::uint64_t tick, const core::Velocity& velocity);
  // Dispatcher events: one is owed (unless it arrived already), one arrived, a mission ended
  // (its id may be used again).
  void Await(const EventKey& event);
  void Seen(const EventKey& event);
  void Forget(std::uint16_t mission_id);
  // A relayed phase status of a mission: LOADING owes a LOADED when `loaded_auto` (the
  // dispatcher sends it on its own after a delay), UNLOADING an UNLOADED when `unloaded_auto`;
  // an ended mission is forgotten.
  void OnPhase(std::uint16_t mission_id, core::MissionPhase phase, bool loaded_auto,
               bool unloaded_auto);

  // A dispatcher's scheduled orders (Mission_Schedule): with ExpectSchedule, tick 1 on waits
  // for the schedule; each order waits from its start tick until it arrived.
  void ExpectSchedule() { expect_schedule_ = true; }
  void OnSchedule(const std::vector<std::pair<std::uint16_t, std::uint64_t>>& orders);
  void OrderArrived(std::uint16_t mission_id);
  // Tick `tick` must wait: for the schedule, or for an order due by then.
  bool OrdersMissing(std::uint64_t tick) const;
  // Stops waiting for what OrdersMissing(tick) waits for; returns the orders given up.
  std::vector<std::uint16_t> GiveUpOrders(std::uint64_t tick);
  bool ScheduleMissing() const { return expect_schedule_ && !have_schedule_; }
  // Statist as dispatcher (SPEC 9.4): the missions recruiting now (id, the tick their statist
  // stands from) and the last tick whose positions the dispatcher has watched. Tick t waits
  // while a recruit started before t and the dispatcher has not watched tick t - 1 (its order
  // may enter at t); GiveUpRecruits(t) stops waiting for that.
  void OnRecruits(std::uint64_t checked_tick,
                  const std::vector<std::pair<std::uint16_t, std::uint64_t>>& recruiting);
  bool RecruitsUnchecked(std::uint64_t tick) const;
  void GiveUpRecruits(std::uint64_t tick);

  // Every live robot asked this tick answered it.
  bool AllAnswered() const { return awaiting_ == 0; }
  // Live robots asked this tick that have not answered, ascending.
  std::vector<std::uint16_t> Late() const;
  std::size_t LiveCount() const;
  // Dispatcher events still missing; GiveUpEvents() stops waiting for them (returns them).
  bool EventsAwaited() const { return !events_awaited_.empty(); }
  std::vector<EventKey> GiveUpEvents();
  // The command a live robot drives this tick: its answer, or zero when it did not answer.
  core::Velocity CommandOf(std::uint16_t id) const;

 private:
  struct Slot {
    bool live = false;
    bool asked = false;       // it got the current tick's perception
    bool has_answer = false;  // ... and answered it
    core::Velocity answer;
  };

  std::uint64_t tick_ = 0;
  std::size_t awaiting_ = 0;  // live robots asked this tick that have not answered
  std::map<std::uint16_t, Slot> robots_;
  bool expect_schedule_ = false;
  bool have_schedule_ = false;
  std::map<std::uint16_t, std::uint64_t> orders_due_;  // scheduled, not arrived: start tick
  std::set<std::uint16_t> orders_early_;               // arrived before the schedule named them
  std::set<EventKey> events_awaited_;
  std::map<std::uint16_t, std::uint64_t> recruits_;  // recruiting mission: statist's first tick
  std::uint64_t recruit_checked_ = 0;
  std::set<EventKey> events_seen_;
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_LOCKSTEP_BARRIER_H_
