// The lock-step barrier [SPEC 7]: when is a tick complete? Pure bookkeeping (no ROS, no
// clock): the simulator's adapter feeds it what arrives and asks it whether to go on.
//
// A tick is complete when every live robot asked answered it - one answer per robot and tick,
// naming the tick and carrying the command and every mission message the robot sends in it, so
// nothing else has to be counted or waited for (issue 10, item 4). With a dispatcher, a tick
// begins once the dispatcher's answers (core/dispatcher_answer.h) name every status relayed
// from the robots, what they name has arrived (its LOADED / UNLOADED; its orders from their
// start ticks), and, from the tick its answers hold, its answer to the previous tick's
// positions. The barrier knows nothing of why the dispatcher sends what it sends.
#ifndef SWARM_TRANSPORT_SIM_LOCKSTEP_BARRIER_H_
#define SWARM_TRANSPORT_SIM_LOCKSTEP_BARRIER_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/core/dispatcher_answer.h"
#include "swarm_transport/core/kinematics.h"

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
  // The dispatcher (lock-step with one). From ExpectDispatcher on, tick 1 on waits for its
  // first answer; each answer replaces which ticks wait for its next.
  void ExpectDispatcher() { hold_from_ = 1; }
  // A status relayed from the robots: the next tick waits until an answer names it.
  void StatusRelayed(const core::StatusKey& status);
  void OnDispatcherAnswer(const core::DispatcherAnswer& answer);
  // The dispatcher's order / LOADED or UNLOADED arrived on its topic (before or after the
  // answer naming it: they travel on different topics).
  void OrderArrived(std::uint16_t mission_id);
  void EventArrived(const EventKey& event);
  // A mission ended (its id may be used again): what arrived for it unnamed is forgotten.
  void Forget(std::uint16_t mission_id);
  // What tick `tick` still waits for from the dispatcher.
  struct DispatcherWait {
    bool answer = false;                    // its answer to the positions of tick - 1
    bool first = false;                     // ... its first answer (none yet)
    std::vector<core::StatusKey> statuses;  // relayed, no answer names them yet
    std::vector<EventKey> events;           // named, not arrived
    std::vector<std::uint16_t> orders;      // named and due by `tick`, not arrived
    bool empty() const { return !answer && statuses.empty() && events.empty() && orders.empty(); }
    // For a log line: "no answer to the positions of tick 4; no LOADED for mission 3".
    std::string Text(std::uint64_t tick) const;
  };
  bool DispatcherPending(std::uint64_t tick) const;
  DispatcherWait WaitsFor(std::uint64_t tick) const;
  // Stops waiting for all of it; returns what was given up.
  DispatcherWait GiveUpDispatcher(std::uint64_t tick);

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

  // Tick `tick` waits for the dispatcher's answer to the previous tick's positions.
  bool AnswerDue(std::uint64_t tick) const;

  std::uint64_t tick_ = 0;
  std::size_t awaiting_ = 0;  // live robots asked this tick that have not answered
  std::map<std::uint16_t, Slot> robots_;
  // The dispatcher's side.
  std::uint64_t hold_from_ = 0;  // ticks from this on wait for its previous tick's answer (0: none)
  bool answered_ = false;        // an answer with positions arrived
  std::uint64_t checked_ = 0;    // the latest tick its answers checked
  std::multiset<core::StatusKey> statuses_owed_;       // relayed, not named yet
  std::map<std::uint16_t, std::uint64_t> orders_due_;  // named, not arrived: start tick
  std::set<std::uint16_t> orders_early_;               // arrived before an answer named them
  std::set<EventKey> events_awaited_;                  // named, not arrived
  std::multiset<EventKey> events_early_;               // arrived before an answer named them
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_LOCKSTEP_BARRIER_H_
