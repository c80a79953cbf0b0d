// The pieces of a real-time robot process's tick (issue 10, item 8): the rule for its next due
// time, a ticker that runs its ticks in roscpp's poll thread, a callback queue that runs a
// subscription's callback in that thread as the message arrives, the mailbox in which its radio
// rounds wait for its next tick, and a queue that runs its other callbacks under its lock.
//
// Why: on roscpp's wall timer and spinner a robot process woke its threads six times per tick -
// the timer's thread, the spinner for the timer's callback, the poll thread for the round, the
// spinner for the round's callback, the poll thread again for the command it published (roscpp
// writes every message from its poll thread), and the spinner's 10 Hz look at ros::ok() - each
// wake-up ~15 us of CPU on a small virtual machine, against a few microseconds of behaviour.
// Ticking in the poll thread (a timerfd in roscpp's own poll set at the robot's due times) and
// taking the round there, a tick wakes it twice: when the round arrives and when the tick is
// due; the command it publishes goes out in the same wake-up.
#ifndef SWARM_TRANSPORT_ROS_TICK_LOOP_H_
#define SWARM_TRANSPORT_ROS_TICK_LOOP_H_

#include <ros/callback_queue_interface.h>

#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/Neighbors.h"

namespace swarm_transport {

using TickClock = std::chrono::steady_clock;

// The tick after the one due at `due` (already run): `due + period`, or, when that is more than
// a period behind `now`, the first due time of the robot's own timeline after `now` - no burst
// of catch-up ticks after a hold-up, and a robot keeps its phase (roscpp's timers reschedule a
// late timer to "now", which lined many robots' ticks up in one burst).
inline TickClock::time_point NextTickDue(TickClock::time_point due, TickClock::duration period,
                                         TickClock::time_point now) {
  TickClock::time_point next = due + period;
  if (period > TickClock::duration::zero() && next + period < now) {
    next += ((now - next) / period + 1) * period;
  }
  return next;
}

// A callback queue that runs every callback at once, in the thread that queues it: for a
// subscription, roscpp's poll thread right after it read the message (roscpp holds the
// subscription's callback lock meanwhile, so the callback must only hand the message on - it
// must not subscribe, unsubscribe or wait for the thread that does). Nothing is ever pending,
// so removing a subscription's callbacks has nothing to remove.
class InlineCallbackQueue : public ros::CallbackQueueInterface {
 public:
  void addCallback(const ros::CallbackInterfacePtr& callback, uint64_t /*owner_id*/) override {
    // Only this thread calls a subscription's queue here: it never has to try again.
    callback->call();
  }
  void removeByID(uint64_t /*owner_id*/) override {}
};

// A robot's radio rounds from the thread that receives them to the thread that ticks, each with
// its arrival time. Thread-safe.
class RoundMailbox {
 public:
  struct Arrived {
    Neighbors::ConstPtr round;
    double wall_s = 0.0;  // ros::WallTime when it arrived
  };

  // A round arrived. At most `limit` wait (the oldest ones go first: they are stale, as a
  // subscription queue of that size drops them; diagnostics count them missed).
  void Put(Neighbors::ConstPtr round, double wall_s, std::size_t limit) {
    std::lock_guard<std::mutex> lock(mutex_);
    if (limit > 0 && rounds_.size() >= limit) {
      rounds_.erase(rounds_.begin(), rounds_.begin() + (rounds_.size() - limit + 1));
    }
    rounds_.push_back(Arrived{std::move(round), wall_s});
  }

  // Every round that arrived since the last call, in arrival order, into `out` (cleared first).
  void TakeAll(std::vector<Arrived>* out) {
    out->clear();
    std::lock_guard<std::mutex> lock(mutex_);
    out->swap(rounds_);
  }

 private:
  std::mutex mutex_;
  std::vector<Arrived> rounds_;
};

// Runs `tick` in roscpp's poll thread at a robot's due times: the first one period after
// Start(), then by NextTickDue (its own timeline: robots tick independently, as on hardware).
// The timer is a timerfd in roscpp's poll set, so that the wake-up that runs a tick also writes
// what the tick published.
class PollThreadTicker {
 public:
  PollThreadTicker() = default;
  ~PollThreadTicker() { Stop(); }
  PollThreadTicker(const PollThreadTicker&) = delete;
  PollThreadTicker& operator=(const PollThreadTicker&) = delete;

  // False (with `error`) when the timer cannot be made.
  bool Start(TickClock::duration period, std::function<void()> tick, std::string* error);
  // No tick starts after it, and none runs when it returns. From any thread but a tick's own.
  void Stop();

 private:
  struct State;
  std::shared_ptr<State> state_;  // shared with the poll set's callback (it may outlive Stop)
};

// A robot process's loop on its own timeline: `ticker` runs `tick` every `period_s` while this
// thread spins the global queue (mission topics, the robot list, services, connections) until
// ROS shuts down (ros::shutdown wakes the wait). False (after one ROS_FATAL naming robot `id`)
// when the timer cannot be made.
bool SpinWithOwnTicks(PollThreadTicker* ticker, double period_s, std::function<void()> tick,
                      unsigned id);

// Runs the callbacks of a robot's node handles on `target` (the thread that spins it), each
// holding `mutex`: the robot's ticks run in another thread (PollThreadTicker) under the same
// lock, so its state is never touched by two threads at once.
class LockedCallbackQueue : public ros::CallbackQueueInterface {
 public:
  LockedCallbackQueue(ros::CallbackQueueInterface* target, std::mutex* mutex)
      : target_(target), mutex_(mutex) {}
  void addCallback(const ros::CallbackInterfacePtr& callback, uint64_t owner_id) override;
  void removeByID(uint64_t owner_id) override { target_->removeByID(owner_id); }

 private:
  ros::CallbackQueueInterface* target_;
  std::mutex* mutex_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_TICK_LOOP_H_
