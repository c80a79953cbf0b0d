// 2D geometry: points, circles, rectangles, composite shapes and zones (danger / safety).
#ifndef SWARM_TRANSPORT_CORE_GEOMETRY_H_
#define SWARM_TRANSPORT_CORE_GEOMETRY_H_

#include <vector>

#include "swarm_transport/core/angle.h"

namespace swarm_transport {
namespace core {

// A point or vector in the arena frame (metres).
struct Vec2 {
  double x = 0.0;
  double y = 0.0;
};
// Inline: a robot's collision search evaluates these millions of times per second.
inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.y + b.y}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.y - b.y}; }
inline Vec2 operator*(Vec2 a, double s) { return {a.x * s, a.y * s}; }
inline double SquaredDistance(Vec2 a, Vec2 b) {
  const double dx = b.x - a.x;
  const double dy = b.y - a.y;
  return dx * dx + dy * dy;
}
// True when Distance(a, b) is certainly greater than d (d >= 0), decided without a square root:
// squares carry a relative rounding error far below the 1e-9 margin, so whenever this says
// true the exact Distance() agrees; when it says false, compute the Distance().
inline bool FartherThan(Vec2 a, Vec2 b, double d) {
  return SquaredDistance(a, b) > d * d * (1.0 + 1e-9);
}
double Norm(Vec2 v);
double Distance(Vec2 a, Vec2 b);
// Bearing of the vector from `from` to `to` (Angle(0) when they coincide).
Angle Bearing(Vec2 from, Vec2 to);
// The unit vector of a heading.
Vec2 UnitVector(Angle heading);
// Shortest distance from p to the segment [a, b].
double DistancePointSegment(Vec2 p, Vec2 a, Vec2 b);

// A circle (centre, radius > 0).
struct Circle {
  Vec2 centre;
  double radius = 0.0;
};

// An axis-aligned rectangle given by its centre and full size (size > 0).
struct Rect {
  Vec2 centre;
  Vec2 size;
};

// One primitive of a composite shape.
struct Primitive {
  enum class Kind { kCircle, kRect };
  Kind kind = Kind::kRect;
  Circle circle;
  Rect rect;
  static Primitive MakeCircle(Vec2 centre, double radius);
  static Primitive MakeRect(Vec2 centre, Vec2 size);
};

// A union of primitives (an L or U shaped object is several rectangles).
class Shape {
 public:
  Shape() = default;
  explicit Shape(std::vector<Primitive> parts) : parts_(std::move(parts)) {}
  static Shape FromRect(Vec2 centre, Vec2 size);
  static Shape FromCircle(Vec2 centre, double radius);

  const std::vector<Primitive>& parts() const { return parts_; }
  bool empty() const { return parts_.empty(); }
  // True when p is inside (or on the border of) any part.
  bool Contains(Vec2 p) const;
  // Distance from p to the shape: 0 when inside.
  double DistanceTo(Vec2 p) const;
  // The nearest point of the shape to p (p itself when inside).
  Vec2 NearestPoint(Vec2 p) const;
  // The nearest point outside the shape to p (p itself when outside); `margin` > 0 steps that
  // far beyond the border.
  Vec2 NearestPointOutside(Vec2 p, double margin) const;
  // Centre of the bounding box of all parts.
  Vec2 Centre() const;
  // Moves every part by `delta`.
  Shape Translated(Vec2 delta) const;

 private:
  std::vector<Primitive> parts_;
};

// A zone a robot must respect. A danger zone (inverted = false) must not be entered; a safety
// zone (inverted = true) must not be left: all outside it is danger [T5.4].
struct Zone {
  int id = 0;  // mission id for object zones, negative for static zones from config
  Shape shape;
  bool inverted = false;
  // True when p is forbidden by this zone (inside a danger zone, or outside a safety zone).
  bool Forbids(Vec2 p) const;
  // The nearest allowed point to p, `margin` inside the allowed region (p when allowed).
  Vec2 NearestAllowedPoint(Vec2 p, double margin) const;
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_GEOMETRY_H_
