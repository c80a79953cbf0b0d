// What a robot node keeps beside its session: with broadcast comm (the thesis's all-to-all
// wiring, for comparison benchmarks) every robot's latest /flock/position, and with
// ~diagnostics its tick timing and delivery figures, one line per wall second.
#ifndef SWARM_TRANSPORT_ROS_ROBOT_STATS_H_
#define SWARM_TRANSPORT_ROS_ROBOT_STATS_H_

#include <cstdint>
#include <map>
#include <string>
#include <utility>

#include "swarm_transport/Neighbors.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/modes.h"
#include "swarm_transport/core/tick_stats.h"

namespace swarm_transport {

// Broadcast comm: what each (robot_id, sub_id) last sent, and when (wall s, radio round).
class BroadcastHeard {
 public:
  // Another robot's (or copy's) position; its own echo and non-finite ones are no news.
  void Hear(std::uint16_t self, const Robot_Position::ConstPtr& msg, double wall_s,
            std::uint64_t round);
  // Its own pose from `round`, and everything every robot sent (the step filters by range);
  // forgets what it has not heard for a few radio rounds.
  core::Perception Perceive(std::uint16_t self, const Neighbors& round);
  // Of the robots the radio says are in range this round, how many there are and those whose
  // own latest position reached this robot in time (real time: it arrived within the last
  // kLateTickFactor periods, as they send one per tick; lock-step: it is their current one).
  std::pair<std::size_t, std::size_t> Delivered(const Neighbors& round, bool realtime, double now_s,
                                                double period_s) const;

 private:
  struct Heard {
    Robot_Position::ConstPtr position;
    double wall_s = 0.0;
    std::uint64_t round = 0;
  };
  std::map<std::pair<std::uint16_t, std::uint8_t>, Heard> heard_;
};

// ~diagnostics of one robot.
class RobotStats {
 public:
  // `own_radio`: the robot assembles its rounds itself (hardware); its transport counts their
  // delivery (CountDelivered), a round's arrival says nothing of it.
  RobotStats(std::uint16_t id, core::Clock clock, core::Comm comm, double period_s,
             bool own_radio = false);
  // A round's arrival at wall time `arrival_s` (and, local comm of the simulator's radio, its
  // updates' delivery).
  void OnRound(const Neighbors& round, double arrival_s);
  // Own radio: of a round's robots, how many there were and how many arrived in time.
  void CountDelivered(std::size_t expected, std::size_t delivered) {
    stats_.CountUpdates(expected, delivered);
  }
  // A tick on `round` (broadcast comm: `heard`, else null); the line of figures when one is due
  // (the first tick's at once: its wall time is the robot's start-up figure), else empty.
  std::string OnTick(const Neighbors& round, const BroadcastHeard* heard);

 private:
  const std::uint16_t id_;
  const core::Clock clock_;
  const core::Comm comm_;
  const double period_s_;
  const bool own_radio_;
  core::TickStats stats_;
  double published_s_ = 0.0;  // 0: none yet
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_ROBOT_STATS_H_
