// (ext, issue 27, item 7) Gathering robots around danger zones, as the object's route goes
// around them (SPEC 9.8): a robot whose straight way to its goal under the object (its slot, or
// the object's centre) comes closer than a clearance to a static danger zone gets waypoints
// around the zones (PlanPath) and heads for them until its goal is in clear sight; a robot that
// starts inside a danger zone first leaves it by the shortest way. For the gathering planners'
// estimate (the selection matrix's X), a routed robot stands for the last corner of its way,
// with the way before that corner as extra length. Pure.
#ifndef SWARM_TRANSPORT_CORE_GATHER_ROUTE_H_
#define SWARM_TRANSPORT_CORE_GATHER_ROUTE_H_

#include <cstddef>
#include <optional>
#include <vector>

#include "swarm_transport/core/assignment.h"
#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/path_planner.h"

namespace swarm_transport {
namespace core {

// A gathering robot's own way to its goal: the waypoints, the goal last (empty: straight for the
// goal), and the one it heads for now.
struct GatherWay {
  std::vector<Vec2> waypoints;
  std::size_t leg = 0;
  // The waypoint to head for from `at`: first passes every waypoint beyond which it already sees
  // the next one clear (SegmentClear), or with half the clearance when it is within `reach_m` of
  // it; none (std::nullopt) once the goal is next: then it drives for its goal as without zones.
  std::optional<Vec2> Next(Vec2 at, const std::vector<Zone>& zones, const PathParams& p,
                           double reach_m);
};

// The way from `from` to `goal` around the danger zones of `zones` (their safety zones are not
// considered). Empty when the straight segment keeps p.clearance_m from every zone. Else: out of
// any danger zone `from` lies in first (its nearest point p.clearance_m outside), then PlanPath's
// waypoints (with no clearance when there is no path with it: a goal at a zone's border); only
// the way out (and the goal) when there is no path at all.
GatherWay PlanGatherWay(Vec2 from, Vec2 goal, const std::vector<Zone>& zones, const PathParams& p);

// The robot as a gathering planner sees it, its way to `goal` routed: unchanged when the way is
// straight; else at the last corner before `goal`, heading along the leg that reaches it, with
// the length of its way up to there in extra_m.
PlannerRobot RoutedForPlanner(const PlannerRobot& robot, Vec2 goal, const std::vector<Zone>& zones,
                              const PathParams& p);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_GATHER_ROUTE_H_
