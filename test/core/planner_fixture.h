// Scenes the planner's tests share: round-number selection parameters, a robot and a target.
#ifndef SWARM_TRANSPORT_TEST_CORE_PLANNER_FIXTURE_H_
#define SWARM_TRANSPORT_TEST_CORE_PLANNER_FIXTURE_H_

#include "swarm_transport/core/assignment.h"

namespace swarm_transport {
namespace core {
namespace planner_fixture {

// V = 1 m per time unit, VA = 90 degrees per time unit, corridor 0.5 m: round numbers.
inline SelectionParams Round(double meet_tolerance) {
  SelectionParams p;
  p.speed_m = 1.0;
  p.turn_deg = 90.0;
  p.corridor_m = 0.5;
  p.meet_tolerance = meet_tolerance;
  return p;
}

inline PlannerRobot Robot(double x, double y, double deg) { return {{x, y}, Angle(deg)}; }
inline PlannerTarget Target(double x, double y) { return {{x, y}, 0.0}; }

}  // namespace planner_fixture
}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_TEST_CORE_PLANNER_FIXTURE_H_
