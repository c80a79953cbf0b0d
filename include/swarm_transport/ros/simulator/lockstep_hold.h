// The simulator's ~hold service (lock-step, issue 13): the run stands before a stated tick -
// markers, tf and services go on - until ~hold with tick 0 releases it.
#ifndef SWARM_TRANSPORT_ROS_LOCKSTEP_HOLD_H_
#define SWARM_TRANSPORT_ROS_LOCKSTEP_HOLD_H_

#include <ros/ros.h>

#include <cstdint>
#include <functional>

#include "swarm_transport/Hold.h"

namespace swarm_transport {

// Answers ~hold against the simulator's tick and stands the lock-step loop while a hold asks
// for it. Runs on the simulator's thread (global queue).
class LockstepHold {
 public:
  // `tick` (ticks so far) and `finished` (the last lock-step tick is done) are the simulator's
  // and must outlive the hold. `hold_at` > 0: hold before that tick from the start (~hold_at).
  LockstepHold(bool lockstep, const std::uint64_t* tick, const bool* finished,
               std::uint64_t hold_at = 0);

  // Offers ~hold on `private_nh` (in real time too: it refuses there).
  void Connect(ros::NodeHandle private_nh);
  void Shutdown();

  // Before the current tick begins: stands while a hold asks for it, calling `wait` (spins the
  // queues, publishes markers) until released or `running` turns false; returns the wall time
  // it stood.
  ros::WallDuration HoldIfAsked(const std::function<bool()>& running,
                                const std::function<void()>& wait);
  // The current tick is under way (between BeginTick and EndTick a hold for it is refused).
  void BeginTick() { tick_begun_ = true; }
  void EndTick() { tick_begun_ = false; }
  bool holding() const { return holding_; }

 private:
  bool OnHold(Hold::Request& req, Hold::Response& res);

  bool lockstep_;
  const std::uint64_t* tick_;
  const bool* finished_;
  ros::ServiceServer srv_;
  std::uint64_t hold_at_ = 0;  // hold before this tick (0: none)
  bool holding_ = false;
  bool tick_begun_ = false;  // tick *tick_ is under way
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_LOCKSTEP_HOLD_H_
