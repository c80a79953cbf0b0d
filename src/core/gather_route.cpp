#include "swarm_transport/core/gather_route.h"

namespace swarm_transport {
namespace core {
namespace {

// Overlapping danger zones: a point pushed out of one may lie in the next; this many pushes at
// most.
constexpr int kMaxEscapes = 4;

}  // namespace

std::optional<Vec2> GatherWay::Next(Vec2 at, const std::vector<Zone>& zones, const PathParams& p,
                                    double reach_m) {
  // Near a waypoint it cannot reach (a robot stands on it) it may go on, but not across a zone's
  // corner: the line to the next one keeps half the clearance there.
  PathParams near = p;
  near.clearance_m = p.clearance_m / 2.0;
  while (leg + 1 < waypoints.size()) {
    const Vec2 next = waypoints[leg + 1];
    if (!SegmentClear(at, next, zones, p) &&
        !(Distance(at, waypoints[leg]) <= reach_m && SegmentClear(at, next, zones, near))) {
      break;
    }
    ++leg;
  }
  if (leg + 1 >= waypoints.size()) return std::nullopt;
  return waypoints[leg];
}

GatherWay PlanGatherWay(Vec2 from, Vec2 goal, const std::vector<Zone>& zones, const PathParams& p) {
  GatherWay way;
  if (zones.empty() || SegmentClear(from, goal, zones, p)) return way;
  // Out of a danger zone first, by the shortest way.
  Vec2 start = from;
  for (int escape = 0; escape < kMaxEscapes; ++escape) {
    bool moved = false;
    for (const Zone& zone : zones) {
      if (zone.inverted || !zone.Forbids(start)) continue;
      start = zone.NearestAllowedPoint(start, p.clearance_m);
      moved = true;
    }
    if (!moved) break;
  }
  if (Distance(start, from) > 0.0) way.waypoints.push_back(start);
  std::optional<std::vector<Vec2>> path = PlanPath(start, goal, zones, p);
  if (!path) {
    PathParams bare = p;
    bare.clearance_m = 0.0;
    path = PlanPath(start, goal, zones, bare);
  }
  if (path) {
    way.waypoints.insert(way.waypoints.end(), path->begin(), path->end());
  } else {
    way.waypoints.push_back(goal);
  }
  return way;
}

PlannerRobot RoutedForPlanner(const PlannerRobot& robot, Vec2 goal, const std::vector<Zone>& zones,
                              const PathParams& p) {
  const GatherWay way = PlanGatherWay(robot.position, goal, zones, p);
  if (way.waypoints.size() < 2) return robot;
  PlannerRobot routed = robot;
  Vec2 at = robot.position;
  routed.extra_m = robot.extra_m;
  for (std::size_t i = 0; i + 1 < way.waypoints.size(); ++i) {
    routed.heading = Bearing(at, way.waypoints[i]);
    routed.extra_m += Distance(at, way.waypoints[i]);
    at = way.waypoints[i];
  }
  routed.position = at;
  return routed;
}

}  // namespace core
}  // namespace swarm_transport
