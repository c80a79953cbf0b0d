// Scenes the core's tests share: quiet flocking parameters, the thesis's transport mission, a
// neighbour at a pose, and the dispatcher's book's robots and status reports.
#ifndef SWARM_TRANSPORT_TEST_CORE_FIXTURES_H_
#define SWARM_TRANSPORT_TEST_CORE_FIXTURES_H_

#include <cstdint>
#include <set>
#include <vector>

#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/core/path_planner.h"

namespace swarm_transport {
namespace core {
namespace fixtures {

// Deterministic flocking: no free will, no cohesion, range 1.0, 0.1 per tick, MinSeparation()
// = 0.11.
inline FlockingParams Quiet() {
  FlockingParams p;
  p.local_range_m = 1.0;
  p.speed_m_per_tick = 0.1;
  p.free_will_deg = 0.0;
  p.cohesion = 0.0;
  p.robot_radius_m = 0.05;
  p.collision_margin = 0.1;
  p.speed_reduction = 0.5;
  p.speed_retries = 2;
  p.zone_margin_m = 0.02;
  return p;
}

// Robots [0, 3), 1 leader (robot 0), a 2 x 2 object at (7, 7) carried to (3, 3).
inline MissionSpec Thesis(std::uint16_t id = 7) {
  MissionSpec m;
  m.id = id;
  m.range_from = 0;
  m.range_to = 3;
  m.leader_number = 1;
  m.object_centre = {7.0, 7.0};
  m.object_size = {2.0, 2.0};
  m.target = {3.0, 3.0};
  return m;
}

// A static danger zone `id`: the rectangle from (x0, y0) to (x1, y1).
inline Zone RectZone(int id, double x0, double y0, double x1, double y1) {
  return Zone{id, Shape::FromRect({(x0 + x1) / 2, (y0 + y1) / 2}, {x1 - x0, y1 - y0}), false};
}

// Path planning that keeps `clearance` (m) from every zone, the rest as defaulted.
inline PathParams WithClearance(double clearance) {
  PathParams p;
  p.clearance_m = clearance;
  return p;
}

// The length of the polyline from `from` through `points` (a planned path or way).
inline double PolylineLength(Vec2 from, const std::vector<Vec2>& points) {
  double length = 0.0;
  for (const Vec2& w : points) {
    length += Distance(from, w);
    from = w;
  }
  return length;
}

// Robot ids [0, n): a swarm the dispatcher's book admits orders for.
inline std::set<std::uint16_t> Robots(int n) {
  std::set<std::uint16_t> ids;
  for (int i = 0; i < n; ++i) ids.insert(static_cast<std::uint16_t>(i));
  return ids;
}

// A first leader's status report of mission `id`: `phase` at `tick`.
inline MissionReport Report(std::uint16_t id, MissionPhase phase, std::uint64_t tick) {
  MissionReport r;
  r.mission_id = id;
  r.phase = phase;
  r.tick = tick;
  return r;
}

// A neighbour `id` of `type` (0 physical, 1 virtual copy, 2 statist) at (x, y) heading
// `heading_deg`.
inline Neighbour Robot(std::uint16_t id, double x, double y, double heading_deg = 0.0,
                       std::uint8_t type = 0) {
  Neighbour n;
  n.id = id;
  n.type = type;
  n.position = {x, y};
  n.heading = Angle(heading_deg);
  return n;
}

// The perceiving robot (id 1) at (x, y) heading `heading_deg`, nothing heard yet.
inline Perception PerceptionAt(double x, double y, double heading_deg) {
  Perception in;
  in.self_id = 1;
  in.self = {{x, y}, Angle(heading_deg)};
  return in;
}

// A physical robot `id` at (x, y) heading `heading_deg`.
inline Neighbour At(std::uint16_t id, double x, double y, double heading_deg = 0.0) {
  Neighbour n;
  n.id = id;
  n.position = {x, y};
  n.heading = Angle(heading_deg);
  return n;
}

}  // namespace fixtures
}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_TEST_CORE_FIXTURES_H_
