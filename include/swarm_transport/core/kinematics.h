// Unicycle kinematics shared by the simulator and the robots' own move prediction, so that
// what a robot predicts is exactly what the simulator executes.
#ifndef SWARM_TRANSPORT_CORE_KINEMATICS_H_
#define SWARM_TRANSPORT_CORE_KINEMATICS_H_

#include <cmath>
#include <cstdint>
#include <cstring>

#include "swarm_transport/core/geometry.h"

namespace swarm_transport {
namespace core {

// A robot pose: position (m) and heading.
struct Pose2 {
  Vec2 position;
  Angle heading;
};

// A velocity command held for a duration: linear (m/s), angular (rad/s).
struct Velocity {
  double linear = 0.0;
  double angular = 0.0;
};

// Exact constant-velocity unicycle motion (a straight line or a circular arc) for `duration`
// seconds. Composes exactly: Integrate(Integrate(p, v, a), v, b) == Integrate(p, v, a + b).
Pose2 Integrate(const Pose2& pose, Velocity velocity, double duration_s);

// Below this turn rate Integrate drives a straight line (the arc formula would divide by ~0).
constexpr double kStraightAngularRadPerS = 1e-12;

// The very same double (every bit: -0 is not 0).
inline bool SameBits(double a, double b) {
  std::uint64_t x = 0;
  std::uint64_t y = 0;
  std::memcpy(&x, &a, sizeof x);
  std::memcpy(&y, &b, sizeof y);
  return x == y;
}

// The cosine and sine of the heading a robot last drove straight on. A robot driving straight
// keeps its heading from one integration sub-step to the next, so the simulator asks for the
// same two values over and over (they were 39 % of the batch engine's time at 10,000 robots);
// and the heading it ends a sub-step with (radians and back, wrapped), the same double while
// its heading and its turn are the very doubles of the sub-step before.
struct HeadingTrig {
  double theta_rad = 0.0;
  double cos = 1.0;
  double sin = 0.0;
  bool valid = false;
  double degrees = 0.0;  // the heading the next three belong to
  double radians = 0.0;  // its radians()
  double turn_rad = 0.0;
  Angle after;  // Angle::FromRadians(radians + turn_rad)
  bool after_valid = false;

  // True when it holds every value a straight sub-step from a heading of `heading_deg` turning
  // `turn` needs (IntegrateRefreshing would recompute none of them).
  bool Holds(double heading_deg, double turn) const {
    return after_valid && valid && SameBits(heading_deg, degrees) && SameBits(turn, turn_rad) &&
           radians == theta_rad && std::signbit(radians) == std::signbit(theta_rad);
  }
};
// Integrate, bit for bit, computing cos and sin only when the heading is not the very double
// `trig` holds (sign of zero included), and the heading it ends with only when heading and
// turn are not the very doubles (every bit) `trig` holds; `trig` then holds the new values.
Pose2 IntegrateRefreshing(const Pose2& pose, Velocity velocity, double duration_s,
                          HeadingTrig* trig);
// The same, inline when `trig` holds all it needs (the simulator's sub-steps of a straight
// drive after the first): IntegrateRefreshing's straight expressions, without a call.
inline Pose2 Integrate(const Pose2& pose, Velocity velocity, double duration_s, HeadingTrig* trig) {
  if (std::fabs(velocity.angular) < kStraightAngularRadPerS &&
      trig->Holds(pose.heading.degrees(), velocity.angular * duration_s)) {
    const double length = velocity.linear * duration_s;
    Pose2 result;
    result.position = {pose.position.x + length * trig->cos, pose.position.y + length * trig->sin};
    result.heading = trig->after;
    return result;
  }
  return IntegrateRefreshing(pose, velocity, duration_s, trig);
}

// One tick's move as the thesis executed it [T6.2, SPEC 4]: turn in place by
// angular * duration, then drive linear * duration straight ahead. This is what the simulator
// does with a cmd_vel (World2D::SetCommand turns at once, then holds the linear part), so a
// robot's prediction of its destination matches the simulation.
Pose2 TurnThenDrive(const Pose2& pose, Velocity velocity, double duration_s);

// The command that turns a robot from `pose` to `heading` and drives `distance` (m) within
// `duration_s`: angular = signed turn / duration, linear = distance / duration.
Velocity CommandFor(const Pose2& pose, Angle heading, double distance, double duration_s);

// Points along the arc from `pose` under `velocity` for `duration_s`, `samples` >= 2 of them,
// the first being the start and the last the destination.
std::vector<Vec2> SampleArc(const Pose2& pose, Velocity velocity, double duration_s, int samples);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_KINEMATICS_H_
