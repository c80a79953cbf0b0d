// Paths around danger (SPEC 9.8, issue 12): a mission whose straight line from the object to
// its target crosses a danger zone gets waypoints around the known static zones - A* over a grid
// of the arena, shortened by line of sight - and its leaders steer along them.
#ifndef SWARM_TRANSPORT_CORE_PATH_PLANNER_H_
#define SWARM_TRANSPORT_CORE_PATH_PLANNER_H_

#include <optional>
#include <vector>

#include "swarm_transport/core/geometry.h"

namespace swarm_transport {
namespace core {

struct PathParams {
  double world_size_m = 11.088889;
  double cell_m = 0.1;       // grid resolution of the search
  double clearance_m = 0.0;  // a path point keeps at least this far from every danger zone
};

// True when every point of the segment a -> b keeps `clearance_m` from every danger zone, stays
// inside every safety zone and inside the arena (checked every cell_m / 2).
bool SegmentClear(Vec2 a, Vec2 b, const std::vector<Zone>& zones, const PathParams& p);

// The waypoints from `from` to `to` (`to` last; `from` not included): {to} when the straight
// line is clear, else the corners of a shortest path on the grid (8-connected), each corner the
// farthest point still in line of sight. `from` may itself be too close to a zone (a robot or
// object starting at a border); std::nullopt when `to` is blocked or no path exists.
std::optional<std::vector<Vec2>> PlanPath(Vec2 from, Vec2 to, const std::vector<Zone>& zones,
                                          const PathParams& p);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_PATH_PLANNER_H_
