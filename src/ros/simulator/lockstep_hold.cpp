#include "swarm_transport/ros/simulator/lockstep_hold.h"

#include <string>

namespace swarm_transport {

LockstepHold::LockstepHold(bool lockstep, const std::uint64_t* tick, const bool* finished,
                           std::uint64_t hold_at)
    : lockstep_(lockstep), tick_(tick), finished_(finished), hold_at_(lockstep ? hold_at : 0) {}

void LockstepHold::Connect(ros::NodeHandle private_nh) {
  srv_ = private_nh.advertiseService("hold", &LockstepHold::OnHold, this);
}

void LockstepHold::Shutdown() { srv_.shutdown(); }

ros::WallDuration LockstepHold::HoldIfAsked(const std::function<bool()>& running,
                                            const std::function<void()>& wait) {
  const ros::WallTime since = ros::WallTime::now();
  if (hold_at_ == 0 || *tick_ < hold_at_) return ros::WallDuration(0.0);
  holding_ = true;
  ROS_INFO("simulator: holding before tick %llu (~hold with tick 0 goes on)",
           static_cast<unsigned long long>(*tick_));
  while (running() && hold_at_ != 0 && *tick_ >= hold_at_) wait();
  holding_ = false;
  ROS_INFO("simulator: going on at tick %llu", static_cast<unsigned long long>(*tick_));
  return ros::WallTime::now() - since;
}

bool LockstepHold::OnHold(Hold::Request& req, Hold::Response& res) {
  const std::uint64_t tick = *tick_;
  res.current_tick = tick;
  res.code = Hold::Response::ERROR;
  if (!lockstep_) {
    res.message = "~hold is for the lock-step clock only";
  } else if (*finished_) {
    res.message = "the run is over (last tick done)";
  } else if (req.tick == 0) {
    hold_at_ = 0;
    res.code = Hold::Response::OK;
    res.message = "going on";
  } else if (req.tick < tick || (req.tick == tick && tick_begun_ && !holding_)) {
    res.message = "tick " + std::to_string(req.tick) + " has begun already (now at tick " +
                  std::to_string(tick) + "): ask for a later one";
  } else {
    hold_at_ = req.tick;
    res.code = Hold::Response::OK;
    res.holding = holding_ && tick == req.tick;
    res.message = (res.holding ? "holding before tick " : "will hold before tick ") +
                  std::to_string(req.tick);
  }
  if (res.code != Hold::Response::OK) ROS_WARN("simulator: ~hold refused: %s", res.message.c_str());
  return true;
}

}  // namespace swarm_transport
