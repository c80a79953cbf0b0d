#include "swarm_transport/ros/robot/robot_stats.h"

#include <ros/time.h>

#include <cmath>
#include <sstream>

#include "swarm_transport/ros/common/conversions.h"

namespace swarm_transport {
namespace {

// Broadcast comm: a robot not heard for this many radio rounds is forgotten.
constexpr std::uint64_t kForgetRounds = 10;
// Lock-step diagnostics: a broadcast position this close to the radio's truth is current.
constexpr double kCurrentPositionM = 0.01;
// Diagnostics: one line per robot per this many wall seconds.
constexpr double kStatsPeriodS = 1.0;

}  // namespace

void BroadcastHeard::Hear(std::uint16_t self, const Robot_Position::ConstPtr& msg, double wall_s,
                          std::uint64_t round) {
  // Its own echo and its own virtual copies are not news (the radio drops them too).
  if (msg->robot_id == self || !IsFinite(*msg)) return;
  Heard& heard = heard_[std::make_pair(msg->robot_id, msg->sub_id)];
  heard.position = msg;
  heard.wall_s = wall_s;
  heard.round = round;
}

core::Perception BroadcastHeard::Perceive(std::uint16_t self, const Neighbors& round) {
  core::Perception in;
  in.self_id = self;
  in.self = ToPose2(round.pose);
  in.others.reserve(heard_.size());
  for (auto it = heard_.begin(); it != heard_.end();) {
    if (it->second.round + kForgetRounds < round.tick) {
      it = heard_.erase(it);
      continue;
    }
    in.others.push_back(ToNeighbour(*it->second.position));
    ++it;
  }
  return in;
}

std::pair<std::size_t, std::size_t> BroadcastHeard::Delivered(const Neighbors& round, bool realtime,
                                                              double now_s, double period_s) const {
  std::size_t expected = 0;
  std::size_t delivered = 0;
  for (const Robot_Position& r : round.robots) {
    if (r.type != Robot_Position::TYPE_PHYSICAL) continue;
    ++expected;
    const auto it = heard_.find(std::make_pair(r.robot_id, std::uint8_t{0}));
    if (it == heard_.end()) continue;
    const bool current =
        realtime ? now_s - it->second.wall_s <= core::kLateTickFactor * period_s
                 : std::hypot(it->second.position->pos_x - r.pos_x,
                              it->second.position->pos_y - r.pos_y) <= kCurrentPositionM;
    delivered += current ? 1 : 0;
  }
  return {expected, delivered};
}

RobotStats::RobotStats(std::uint16_t id, core::Clock clock, core::Comm comm, double period_s,
                       bool own_radio)
    : id_(id),
      clock_(clock),
      comm_(comm),
      period_s_(period_s),
      own_radio_(own_radio),
      stats_(period_s, clock == core::Clock::kRealtime) {}

void RobotStats::OnRound(const Neighbors& round, double arrival_s) {
  const double latency = stats_.OnRound(round.tick, round.sim_time, arrival_s);
  if (comm_ != core::Comm::kLocal || own_radio_) return;
  // Local comm: the round carries the in-range robots' updates, delivered within one tick
  // when it arrived within one period of being sampled; a round that never arrived lost as
  // many as this one carries.
  std::size_t in_range = 0;
  for (const Robot_Position& r : round.robots) {
    if (r.type == Robot_Position::TYPE_PHYSICAL) ++in_range;
  }
  stats_.CountUpdates(in_range * (1 + stats_.last_gap()), latency <= period_s_ ? in_range : 0);
}

std::string RobotStats::OnTick(const Neighbors& round, const BroadcastHeard* heard) {
  const double now = ros::WallTime::now().toSec();
  stats_.OnTick(now);
  if (heard != nullptr) {
    const std::pair<std::size_t, std::size_t> d =
        heard->Delivered(round, clock_ == core::Clock::kRealtime, now, period_s_);
    stats_.CountUpdates(d.first, d.second);
  }
  if (published_s_ != 0.0 && now - published_s_ < kStatsPeriodS) return std::string();
  published_s_ = now;
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(6);
  os << "id=" << id_ << " clock=" << core::ClockName(clock_) << " comm=" << core::CommName(comm_)
     << " wall=" << now << " " << stats_.TakeLine();
  return os.str();
}

}  // namespace swarm_transport
