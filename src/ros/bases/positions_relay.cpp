#include "swarm_transport/ros/bases/positions_relay.h"

#include <cmath>
#include <string>

#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/ros/common/names.h"
#include "swarm_transport/ros/common/params.h"

namespace swarm_transport {
namespace {

// Every robot announces once per tick: the queue holds a large swarm's tick.
constexpr std::uint32_t kPositionQueue = 10000;

}  // namespace

bool PositionsRelay::Initialize() {
  std::string error;
  nh_.param("/swarm/tick_period_s", tick_period_s_, tick_period_s_);
  if (!ReadPrivate(private_nh_, "heard_timeout_s", &heard_timeout_s_, &error)) {
  } else if (!std::isfinite(tick_period_s_) || tick_period_s_ <= 0.0) {
    error = "/swarm/tick_period_s must be > 0 but is " + std::to_string(tick_period_s_);
  } else if (!std::isfinite(heard_timeout_s_) || heard_timeout_s_ <= 0.0) {
    error = "~heard_timeout_s must be an age > 0 (s) but is " + std::to_string(heard_timeout_s_);
  }
  if (!error.empty()) {
    ROS_FATAL("positions: invalid parameters: %s", error.c_str());
    return false;
  }
  positions_pub_ = nh_.advertise<Robot_Positions>(names::kWorldPoses, 10, true);
  robots_pub_ = nh_.advertise<Robot_Positions>(names::kRobots, 1, true);
  position_sub_ = nh_.subscribe(names::kPosition, kPositionQueue, &PositionsRelay::OnPosition, this,
                                ros::TransportHints().tcpNoDelay());
  start_ = ros::WallTime::now();
  timer_ = nh_.createWallTimer(ros::WallDuration(tick_period_s_),
                               [this](const ros::WallTimerEvent&) { OnTick(); });
  ROS_INFO("positions: %s every %.3f s from %s (robots silent for %.2f s left out)",
           names::kWorldPoses, tick_period_s_, names::kPosition, heard_timeout_s_);
  return true;
}

void PositionsRelay::OnPosition(const Robot_Position::ConstPtr& msg) {
  if (msg->type != Robot_Position::TYPE_PHYSICAL) return;
  if (!std::isfinite(msg->pos_x) || !std::isfinite(msg->pos_y)) return;
  roster_changed_ = roster_changed_ || heard_.count(msg->robot_id) == 0;
  heard_[msg->robot_id] = Heard{*msg, ros::WallTime::now().toSec()};
}

void PositionsRelay::OnTick() {
  const double now_s = ros::WallTime::now().toSec();
  if (roster_changed_) {
    roster_changed_ = false;
    Robot_Positions list;
    for (const auto& entry : heard_) list.robots.push_back(entry.second.position);
    robots_pub_.publish(list);
  }
  Robot_Positions all;
  all.tick = tick_++;
  all.sim_time = (ros::WallTime::now() - start_).toSec();
  for (const auto& entry : heard_) {
    if (now_s - entry.second.at_s <= heard_timeout_s_) all.robots.push_back(entry.second.position);
  }
  positions_pub_.publish(all);
}

}  // namespace swarm_transport
