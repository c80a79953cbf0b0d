// What a robot node says about itself: its ~state and ~describe services, its diagnostics, and a
// throttled line for each kind of message it rejected.
#include <string>

#include "swarm_transport/ros/robot/robot_node.h"
#include "swarm_transport/ros/robot/robot_report.h"

namespace swarm_transport {
namespace {

// A robot logs one line per kind of rejected message per this many wall seconds (a flood of bad
// messages must not flood the log; issue 11).
constexpr double kRejectLogPeriodS = 10.0;

}  // namespace

void RobotNode::Say(const core::RobotSession::Taken& taken) {
  switch (taken.say) {
    case core::RobotSession::Taken::Say::kNothing:
      return;
    case core::RobotSession::Taken::Say::kDebug:
      ROS_DEBUG("robot %u: ignored: %s", id_, taken.why.c_str());
      return;
    case core::RobotSession::Taken::Say::kWarn: {
      WarnThrottle& throttle = rejected_.try_emplace(taken.kind, kRejectLogPeriodS).first->second;
      if (!throttle.Due()) return;
      ROS_WARN("robot %u: rejected %s%s", id_, taken.why.c_str(),
               throttle.AndMore(taken.kind).c_str());
      return;
    }
  }
}

void RobotNode::PublishStatusIfDue() {
  if (!diagnostics_) return;
  diagnostics_->PublishIfDue(
      [this](NodeStatus* s) { FillStatus(State(), perception_ ? perception_->tick : 0, s); });
}

Robot_State::Response RobotNode::State() const {
  Robot_State::Response state = StateOf(*session_, ticks_, listed_);  // both -1 there
  if (!lockstep() && perception_) {
    state.round_age_s = round_watch_.AgeS(ros::WallTime::now().toSec());
    state.round_waits = round_waits_;
    state.late_command_rounds = echo_.unseen();
  }
  state.command_listeners = transport_->CommandListeners();
  return state;
}

bool RobotNode::OnState(Robot_State::Request& /*req*/, Robot_State::Response& res) {
  res = State();
  return true;
}

bool RobotNode::OnDescribe(std_srvs::Trigger::Request& /*req*/, std_srvs::Trigger::Response& res) {
  res.success = true;
  res.message = Describe(State());
  return true;
}

}  // namespace swarm_transport
