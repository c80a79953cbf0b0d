#include "swarm_transport/core/command_echo.h"

#include <cmath>

namespace swarm_transport {
namespace core {

Pose2 CommandEcho::PlanFrom(const Pose2& round_pose) {
  if (!pending_) return round_pose;
  pending_ = false;
  const double turn_deg = command_.angular * duration_s_ * 180.0 / M_PI;
  if (!(std::fabs(turn_deg) >= kMinTurnDeg)) return round_pose;
  const Angle turned = from_.heading + Angle(turn_deg);
  const double off_turned = std::fabs(Angle::SignedDifference(round_pose.heading, turned));
  const double off_before = std::fabs(Angle::SignedDifference(round_pose.heading, from_.heading));
  if (!(off_before < off_turned)) return round_pose;
  ++unseen_;
  return TurnThenDrive(round_pose, command_, duration_s_);
}

void CommandEcho::Sent(const Pose2& planned_from, const Velocity& command, double duration_s) {
  pending_ = std::isfinite(command.linear) && std::isfinite(command.angular) && duration_s > 0.0;
  from_ = planned_from;
  command_ = command;
  duration_s_ = duration_s;
}

}  // namespace core
}  // namespace swarm_transport
