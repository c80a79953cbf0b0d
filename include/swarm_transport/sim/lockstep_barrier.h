// The lock-step barrier [SPEC 7]: when is a tick complete? Pure bookkeeping (no ROS, no
// clock): the simulator's adapter feeds it what arrives and asks it whether to go on.
//
// A tick is complete when every live robot answered the tick's perception with a command,
// sent its tick_done (if it sends them), and every mission message its process announced in
// tick_done arrived (counted per publishing node: a host runs many robots in one node); and,
// with a dispatcher, when every LOADED / UNLOADED it owes for a relayed LOADING / UNLOADING
// arrived (it is stamped with the tick at which it applies).
#ifndef SWARM_TRANSPORT_SIM_LOCKSTEP_BARRIER_H_
#define SWARM_TRANSPORT_SIM_LOCKSTEP_BARRIER_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/core/kinematics.h"

namespace swarm_transport {
namespace sim {

class LockstepBarrier {
 public:
  using EventKey = std::pair<std::uint16_t, std::uint8_t>;  // (mission id, event kind)

  // What a command did to the barrier.
  enum class Command {
    kAnswer,       // the answer to the current tick
    kStale,        // the late answer to an earlier tick: ignored
    kUnsolicited,  // more commands than perceptions: ignored
    kOutside,      // the robot is not live: not the barrier's business
  };

  // Robots. A robot must be added before anything else about it counts.
  void Add(std::uint16_t id);
  void Remove(std::uint16_t id);
  bool Has(std::uint16_t id) const { return robots_.count(id) != 0; }
  bool Live(std::uint16_t id) const;
  // It publishes tick_done: every tick waits for it, from its first tick on.
  void SendsTickDone(std::uint16_t id);
  // It is connected: from the next perception on it must answer every tick.
  void MakeLive(std::uint16_t id);
  void MakeNotLive(std::uint16_t id);
  // A live robot that answered only older ticks this tick missed a perception: its next
  // answer counts for the next tick. True when it was resynchronised.
  bool Resynchronise(std::uint16_t id);
  // No robot is asked anything any more (the last tick is over).
  void EndAll();

  // A tick: `Ask` each live robot that gets a perception (after StartTick).
  void StartTick(std::uint64_t tick);
  void Ask(std::uint16_t id);
  Command OnCommand(std::uint16_t id, const core::Velocity& velocity);
  // `publisher`: the node that sent it; `events_published`: mission messages its robots sent
  // so far (cumulative per robot).
  void OnTickDone(std::uint16_t id, const std::string& publisher, std::uint64_t tick,
                  std::uint64_t events_published);
  // A mission message the robots announce (counted per publisher) arrived.
  void OnRobotMessage(const std::string& publisher);
  // Dispatcher events: one is owed (unless it arrived already), one arrived, a mission ended
  // (its id may be used again).
  void Await(const EventKey& event);
  void Seen(const EventKey& event);
  void Forget(std::uint16_t mission_id);

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

  // Every live robot's tick is complete.
  bool AllAnswered() const;
  // Live robots whose tick is not complete, ascending.
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
    std::uint64_t asked = 0;     // perceptions sent while live
    std::uint64_t answered = 0;  // commands received while live; == asked: answered
    bool has_answer = false;     // the current tick's command arrived
    bool stale = false;          // an old tick's answer arrived during the current tick
    core::Velocity answer;
    bool sends_tick_done = false;
    bool done = false;           // the current tick's tick_done arrived
    std::string publisher;       // its node
    std::uint64_t events_announced = 0;
  };
  bool Complete(const Slot& slot) const;

  std::uint64_t tick_ = 0;
  std::size_t awaiting_ = 0;  // live robots asked this tick that have not answered
  std::map<std::uint16_t, Slot> robots_;
  std::map<std::string, std::uint64_t> received_;   // per publisher
  std::map<std::string, std::uint64_t> announced_;  // per publisher
  bool expect_schedule_ = false;
  bool have_schedule_ = false;
  std::map<std::uint16_t, std::uint64_t> orders_due_;  // scheduled, not arrived: start tick
  std::set<std::uint16_t> orders_early_;  // arrived before the schedule named them
  std::set<EventKey> events_awaited_;
  std::set<EventKey> events_seen_;
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_LOCKSTEP_BARRIER_H_
