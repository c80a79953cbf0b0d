// The threads of a host of many robots (robot_host.h): in real time a worker per callback queue
// ticks its robots and hands them their rounds (HostWorker), and the robots' diagnostics lines
// go out batched (StatsBatch).
#ifndef SWARM_TRANSPORT_ROS_HOST_WORKER_H_
#define SWARM_TRANSPORT_ROS_HOST_WORKER_H_

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <queue>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "swarm_transport/Neighbors.h"
#include "swarm_transport/ros/robot/robot_transport.h"
#include "swarm_transport/ros/robot/tick_loop.h"

namespace swarm_transport {

// ~diagnostics of a host: its robots' /flock/robot_stats lines, several in one message (one
// per line) at most every 50 ms of wall time. A message per robot and second cost a seventh of
// a 2,000-robot process (roscpp's poll thread woken for every one). Thread-safe.
class StatsBatch {
 public:
  explicit StatsBatch(ros::NodeHandle nh);
  void Add(const std::string& line);
  // Sends what waits when 50 ms passed since the last message.
  void FlushIfDue();

 private:
  void FlushLocked(const ros::WallTime& now);
  std::mutex mutex_;
  ros::Publisher pub_;
  std::string lines_;
  ros::WallTime last_;
};

// Real time: one thread runs a share of the robots - their ticks from one heap of due times,
// their radio rounds (the simulator of this process hands them over once per round) and their
// roscpp callbacks (subscriptions, services) from their callback queue - so one robot's
// callbacks never overlap, and nothing passes through a callback queue per robot and tick.
// Until 2026-11-25 every tick and every round was a callback-queue entry of its own
// (CallbackQueue::addCallback, getIDInfo, their mutexes and wake-ups: ~15 % of the process at
// 2,000 robots). A tick is rescheduled at due + period or, when the robot fell more than a
// period behind, at the first due time of its own timeline after now: no burst of catch-up
// ticks, and the robots' phases stay spread over the period (a worker held up for a moment,
// as by the first /flock/robots of thousands of robots, rescheduling them all to "now" as
// roscpp's timers do, made them tick in one burst of 10-20 ms every period from then on).
class HostWorker {
 public:
  using Clock = TickClock;

  // `stats` (may be null): the host's diagnostics lines, flushed when due at every wake-up.
  HostWorker(ros::CallbackQueue* queue, double period_s, StatsBatch* stats)
      : queue_(queue),
        stats_(stats),
        period_(
            std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period_s))),
        slack_(std::min<Clock::duration>(std::chrono::milliseconds(1), period_ / 100)) {}
  ~HostWorker() { Stop(); }

  // Robot `robot` first ticks `phase` after the worker starts, or after now when it runs
  // already (a robot that joins). The returned slot is the robot's for Stage() and Remove().
  void* Add(RobotInbox* robot, Clock::duration phase) {
    Slot* slot = nullptr;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      slots_.push_back(std::make_unique<Slot>());
      slot = slots_.back().get();
      slot->robot = robot;
      // Before Start(): due times count from the epoch until Start() moves them to its now.
      heap_.push(Entry{(started_ ? Clock::now() : Clock::time_point()) + phase, slot});
    }
    Wake();
    return slot;
  }

  // The robot ticks and hears no more; returns when none of its ticks or rounds runs (from
  // any thread but this worker's).
  void Remove(void* handle) {
    Slot* slot = static_cast<Slot*>(handle);
    std::unique_lock<std::mutex> lock(mutex_);
    slot->robot = nullptr;
    slot->pending.reset();
    idle_.wait(lock, [&] { return running_ != slot; });
  }

  // The simulator's thread: the robot's round of this radio round (handed over by Flush).
  void Stage(void* handle, Neighbors::ConstPtr round) {
    staged_.emplace_back(static_cast<Slot*>(handle), std::move(round));
  }

  // The simulator's thread: hands the staged rounds over. A robot that has not taken its
  // last round yet gets the latest only, as a neighbors subscription with a short queue drops
  // old rounds (its diagnostics count them as missed).
  void Flush() {
    if (staged_.empty()) return;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      for (auto& entry : staged_) {
        Slot* slot = entry.first;
        if (slot->robot == nullptr) continue;
        if (!slot->pending) dirty_.push_back(slot);
        slot->pending = std::move(entry.second);
      }
    }
    staged_.clear();
    Wake();
  }

  // The initial robots' phases count from now: they were added while the robots were set up
  // (thousands take seconds).
  void Start() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      std::vector<Entry> entries;
      for (; !heap_.empty(); heap_.pop()) entries.push_back(heap_.top());
      const Clock::time_point now = Clock::now();
      for (Entry& entry : entries) {
        entry.due = now + entry.due.time_since_epoch();
        heap_.push(entry);
      }
      started_ = true;
    }
    thread_ = std::thread(&HostWorker::Run, this);
  }

  void Stop() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stop_ = true;
    }
    Wake();
    if (thread_.joinable()) thread_.join();
  }

 private:
  struct Slot {
    RobotInbox* robot = nullptr;  // null: removed
    Neighbors::ConstPtr pending;  // its latest round not taken yet
  };
  struct Entry {
    Clock::time_point due;
    Slot* slot;
    bool operator>(const Entry& other) const { return due > other.due; }
  };
  // Does nothing: its arrival ends the worker's wait on the callback queue.
  class WakeCall : public ros::CallbackInterface {
   public:
    CallResult call() override { return Success; }
  };

  void Wake() {
    bool wake = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      wake = !wake_queued_;
      wake_queued_ = true;
    }
    if (wake) queue_->addCallback(boost::make_shared<WakeCall>(), kWakeId);
  }

  // Runs `call` for the slot's robot unless it was removed; Remove() waits for it.
  template <typename F>
  bool RunFor(Slot* slot, F call) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (slot->robot == nullptr) return false;
      running_ = slot;
    }
    call(slot->robot);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      running_ = nullptr;
    }
    idle_.notify_all();
    return true;
  }

  // Runs the ticks due by now, and those due within the slack (1 % of the period, at most 1 ms:
  // a tick that early is no tick late, and thousands of robots cost one wake-up per slack, not
  // one per tick); returns how long until the next one (at most a period).
  Clock::duration RunDueTicks() {
    for (;;) {
      Entry top;
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (heap_.empty()) return period_;
        const Clock::time_point now = Clock::now();
        if (heap_.top().due > now + slack_) return std::min(period_, heap_.top().due - now);
        top = heap_.top();
        heap_.pop();
      }
      if (!RunFor(top.slot, [](RobotInbox* robot) { robot->TimerTick(); })) continue;
      // More than a period behind: its next due time on its own timeline after now.
      const Clock::time_point next = NextTickDue(top.due, period_, Clock::now());
      std::lock_guard<std::mutex> lock(mutex_);
      heap_.push(Entry{next, top.slot});
    }
  }

  void Run() {
    std::vector<std::pair<Slot*, Neighbors::ConstPtr>> rounds;
    for (;;) {
      {
        std::lock_guard<std::mutex> lock(mutex_);
        if (stop_) return;
        wake_queued_ = false;
        for (Slot* slot : dirty_) rounds.emplace_back(slot, std::move(slot->pending));
        dirty_.clear();
      }
      // The rounds in the order they were delivered (ascending id), a few at a time between
      // the ticks that fall due meanwhile: a whole round of thousands of robots at once would
      // hold their ticks back by milliseconds.
      for (std::size_t k = 0; k < rounds.size(); ++k) {
        if (k % kRoundsBetweenTicks == 0) RunDueTicks();
        if (rounds[k].second) {
          RunFor(rounds[k].first, [&](RobotInbox* robot) {
            robot->TakeRound(rounds[k].second, ros::WallTime::now().toSec());
          });
        }
      }
      rounds.clear();
      const Clock::duration wait = RunDueTicks();
      if (stats_ != nullptr) stats_->FlushIfDue();
      // The robots' roscpp callbacks, and the wait for the next tick or a wake-up.
      queue_->callAvailable(ros::WallDuration(std::chrono::duration<double>(wait).count()));
    }
  }

  static constexpr std::size_t kRoundsBetweenTicks = 32;
  static constexpr std::uint64_t kWakeId = 1;  // no robot's address

  ros::CallbackQueue* queue_;
  StatsBatch* stats_;
  const Clock::duration period_;
  const Clock::duration slack_;
  std::mutex mutex_;
  std::condition_variable idle_;
  std::vector<std::unique_ptr<Slot>> slots_;  // kept until the worker goes (Remove() only marks)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<Entry>> heap_;
  std::vector<Slot*> dirty_;  // slots with a pending round
  Slot* running_ = nullptr;
  bool wake_queued_ = false;
  bool started_ = false;
  bool stop_ = false;
  std::vector<std::pair<Slot*, Neighbors::ConstPtr>> staged_;  // the simulator's thread only
  std::thread thread_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_HOST_WORKER_H_
