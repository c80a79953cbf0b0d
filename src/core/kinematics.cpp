#include "swarm_transport/core/kinematics.h"

#include <cmath>
#include <stdexcept>

namespace swarm_transport {
namespace core {

Pose2 Integrate(const Pose2& pose, Velocity velocity, double duration_s) {
  const double theta = pose.heading.radians();
  const double turn = velocity.angular * duration_s;
  Pose2 result;
  if (std::fabs(velocity.angular) < kStraightAngularRadPerS) {
    const double length = velocity.linear * duration_s;
    result.position = {pose.position.x + length * std::cos(theta),
                       pose.position.y + length * std::sin(theta)};
  } else {
    const double radius = velocity.linear / velocity.angular;
    result.position = {pose.position.x + radius * (std::sin(theta + turn) - std::sin(theta)),
                       pose.position.y - radius * (std::cos(theta + turn) - std::cos(theta))};
  }
  result.heading = Angle::FromRadians(theta + turn);
  return result;
}

Pose2 IntegrateRefreshing(const Pose2& pose, Velocity velocity, double duration_s,
                          HeadingTrig* trig) {
  if (!(std::fabs(velocity.angular) < kStraightAngularRadPerS)) {
    return Integrate(pose, velocity, duration_s);
  }
  // Integrate's straight branch with the same expressions; what depends on the heading alone
  // (radians, cos, sin) or on heading and turn alone (the heading after) from `trig` when
  // those are the very doubles it holds.
  const double degrees = pose.heading.degrees();
  const double turn = velocity.angular * duration_s;
  if (!trig->after_valid || !SameBits(degrees, trig->degrees)) {
    trig->degrees = degrees;
    trig->radians = pose.heading.radians();
    trig->after_valid = false;
  }
  const double theta = trig->radians;
  if (!trig->valid || !(theta == trig->theta_rad) ||
      std::signbit(theta) != std::signbit(trig->theta_rad)) {
    trig->theta_rad = theta;
    trig->cos = std::cos(theta);
    trig->sin = std::sin(theta);
    trig->valid = true;
  }
  if (!trig->after_valid || !SameBits(turn, trig->turn_rad)) {
    trig->turn_rad = turn;
    trig->after = Angle::FromRadians(theta + turn);
    trig->after_valid = true;
  }
  const double length = velocity.linear * duration_s;
  Pose2 result;
  result.position = {pose.position.x + length * trig->cos, pose.position.y + length * trig->sin};
  result.heading = trig->after;
  return result;
}

Velocity CommandFor(const Pose2& pose, Angle heading, double distance, double duration_s) {
  if (!(duration_s > 0.0)) throw std::invalid_argument("CommandFor: duration_s must be > 0");
  // The shortest signed turn, so a robot never spins the long way round.
  const double turn_rad = Angle::SignedDifference(heading, pose.heading) * M_PI / 180.0;
  return Velocity{distance / duration_s, turn_rad / duration_s};
}

std::vector<Vec2> SampleArc(const Pose2& pose, Velocity velocity, double duration_s, int samples) {
  if (samples < 2) throw std::invalid_argument("SampleArc: samples must be >= 2");
  std::vector<Vec2> points;
  points.reserve(static_cast<std::size_t>(samples));
  for (int i = 0; i < samples; ++i) {
    // The last sample uses duration_s itself so that it equals Integrate's destination exactly.
    const double t = i == samples - 1 ? duration_s : duration_s * i / (samples - 1);
    points.push_back(Integrate(pose, velocity, t).position);
  }
  return points;
}

Pose2 TurnThenDrive(const Pose2& pose, Velocity velocity, double duration_s) {
  Pose2 turned = pose;
  turned.heading = pose.heading + Angle::FromRadians(velocity.angular * duration_s);
  return Integrate(turned, Velocity{velocity.linear, 0.0}, duration_s);
}

}  // namespace core
}  // namespace swarm_transport
