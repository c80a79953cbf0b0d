#include "swarm_transport/core/geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace swarm_transport {
namespace core {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A point counts as strictly inside a part only deeper than this, so that border points
// computed with rounding errors still count as border points.
constexpr double kInsideTolerance = 1e-9;
// Segments whose direction cross product is below this are treated as parallel.
constexpr double kParallelTolerance = 1e-15;

// One side of a rectangle.
struct Side {
  Vec2 a;
  Vec2 b;
};

double Dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double Cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

Vec2 ClosestOnSegment(Vec2 p, Vec2 a, Vec2 b) {
  const Vec2 ab = b - a;
  const double length_sq = Dot(ab, ab);
  if (length_sq == 0.0) return a;
  const double t = std::clamp(Dot(p - a, ab) / length_sq, 0.0, 1.0);
  return a + ab * t;
}

std::vector<Side> SidesOf(const Rect& rect) {
  const Vec2 lo = rect.centre - rect.size * 0.5;
  const Vec2 hi = rect.centre + rect.size * 0.5;
  return {{{lo.x, lo.y}, {hi.x, lo.y}},
          {{hi.x, lo.y}, {hi.x, hi.y}},
          {{hi.x, hi.y}, {lo.x, hi.y}},
          {{lo.x, hi.y}, {lo.x, lo.y}}};
}

// How deep p lies inside a part: > 0 inside, 0 on the border, < 0 outside.
double Depth(const Primitive& part, Vec2 p) {
  if (part.kind == Primitive::Kind::kCircle) {
    return part.circle.radius - Distance(p, part.circle.centre);
  }
  const Vec2 d = p - part.rect.centre;
  return std::min(part.rect.size.x * 0.5 - std::fabs(d.x), part.rect.size.y * 0.5 - std::fabs(d.y));
}

Vec2 NearestPointOfPart(const Primitive& part, Vec2 p) {
  if (part.kind == Primitive::Kind::kCircle) {
    const double d = Distance(p, part.circle.centre);
    if (d <= part.circle.radius) return p;
    return part.circle.centre + (p - part.circle.centre) * (part.circle.radius / d);
  }
  const Vec2 lo = part.rect.centre - part.rect.size * 0.5;
  const Vec2 hi = part.rect.centre + part.rect.size * 0.5;
  return {std::clamp(p.x, lo.x, hi.x), std::clamp(p.y, lo.y, hi.y)};
}

// The nearest point to p that lies `margin` inside the part (its centre when the part is not
// that thick).
Vec2 NearestInsetPointOfPart(const Primitive& part, Vec2 p, double margin) {
  if (part.kind == Primitive::Kind::kCircle) {
    const double inner = part.circle.radius - margin;
    if (inner <= 0.0) return part.circle.centre;
    const double d = Distance(p, part.circle.centre);
    if (d <= inner) return p;
    return part.circle.centre + (p - part.circle.centre) * (inner / d);
  }
  const Rect& rect = part.rect;
  auto inset = [margin](double value, double centre, double size) {
    if (size <= 2.0 * margin) return centre;
    const double half = size * 0.5 - margin;
    return std::clamp(value, centre - half, centre + half);
  };
  return {inset(p.x, rect.centre.x, rect.size.x), inset(p.y, rect.centre.y, rect.size.y)};
}

// The axis-aligned bounding box of a non-empty list of parts.
void BoundingBox(const std::vector<Primitive>& parts, Vec2* lo, Vec2* hi) {
  *lo = {kInfinity, kInfinity};
  *hi = {-kInfinity, -kInfinity};
  for (const Primitive& part : parts) {
    const bool is_circle = part.kind == Primitive::Kind::kCircle;
    const Vec2 centre = is_circle ? part.circle.centre : part.rect.centre;
    const Vec2 extent =
        is_circle ? Vec2{part.circle.radius, part.circle.radius} : part.rect.size * 0.5;
    *lo = {std::min(lo->x, centre.x - extent.x), std::min(lo->y, centre.y - extent.y)};
    *hi = {std::max(hi->x, centre.x + extent.x), std::max(hi->y, centre.y + extent.y)};
  }
}

// The part grown by `margin` on every side. A rectangle keeps square corners: its corner
// points lie up to margin * sqrt(2) away, never closer than the margin.
Primitive Inflated(const Primitive& part, double margin) {
  if (part.kind == Primitive::Kind::kCircle) {
    return Primitive::MakeCircle(part.circle.centre, part.circle.radius + margin);
  }
  return Primitive::MakeRect(part.rect.centre, part.rect.size + Vec2{2.0 * margin, 2.0 * margin});
}

// The points of the part's border nearest to p: the foot on every side of a rectangle (not
// only the nearest side, which may lie inside another part), the radial point of a circle.
void AddBorderPoints(const Primitive& part, Vec2 p, std::vector<Vec2>* out) {
  if (part.kind == Primitive::Kind::kCircle) {
    const Vec2 offset = p - part.circle.centre;
    const double length = Norm(offset);
    // From the centre every direction is nearest: take +x.
    const Vec2 direction = length > 0.0 ? offset * (1.0 / length) : Vec2{1.0, 0.0};
    out->push_back(part.circle.centre + direction * part.circle.radius);
    return;
  }
  for (const Side& side : SidesOf(part.rect)) out->push_back(ClosestOnSegment(p, side.a, side.b));
}

void AddSegmentIntersection(const Side& s, const Side& t, std::vector<Vec2>* out) {
  const Vec2 ds = s.b - s.a;
  const Vec2 dt = t.b - t.a;
  const double denominator = Cross(ds, dt);
  // Parallel sides cross nowhere or along a stretch whose ends are crossings of other sides.
  if (std::fabs(denominator) < kParallelTolerance) return;
  const double u = Cross(t.a - s.a, dt) / denominator;
  const double v = Cross(t.a - s.a, ds) / denominator;
  if (u < 0.0 || u > 1.0 || v < 0.0 || v > 1.0) return;
  out->push_back(s.a + ds * u);
}

void AddSegmentCircleIntersections(const Side& s, const Circle& c, std::vector<Vec2>* out) {
  const Vec2 d = s.b - s.a;
  const Vec2 f = s.a - c.centre;
  const double a = Dot(d, d);
  const double b = 2.0 * Dot(f, d);
  const double discriminant = b * b - 4.0 * a * (Dot(f, f) - c.radius * c.radius);
  if (a == 0.0 || discriminant < 0.0) return;
  for (const double sign : {-1.0, 1.0}) {
    const double t = (-b + sign * std::sqrt(discriminant)) / (2.0 * a);
    if (t >= 0.0 && t <= 1.0) out->push_back(s.a + d * t);
  }
}

void AddCircleIntersections(const Circle& c1, const Circle& c2, std::vector<Vec2>* out) {
  const double d = Distance(c1.centre, c2.centre);
  if (d == 0.0 || d > c1.radius + c2.radius || d < std::fabs(c1.radius - c2.radius)) return;
  const double along = (d * d + c1.radius * c1.radius - c2.radius * c2.radius) / (2.0 * d);
  const double across = std::sqrt(std::max(0.0, c1.radius * c1.radius - along * along));
  const Vec2 axis = (c2.centre - c1.centre) * (1.0 / d);
  const Vec2 perpendicular{-axis.y, axis.x};
  for (const double sign : {-1.0, 1.0}) {
    out->push_back(c1.centre + axis * along + perpendicular * (sign * across));
  }
}

// Where the borders of two parts cross: the inner corners of a union.
void AddBorderIntersections(const Primitive& first, const Primitive& second,
                            std::vector<Vec2>* out) {
  const bool first_is_circle = first.kind == Primitive::Kind::kCircle;
  const bool second_is_circle = second.kind == Primitive::Kind::kCircle;
  if (first_is_circle && second_is_circle) {
    AddCircleIntersections(first.circle, second.circle, out);
  } else if (first_is_circle || second_is_circle) {
    const Circle& circle = first_is_circle ? first.circle : second.circle;
    const Rect& rect = first_is_circle ? second.rect : first.rect;
    for (const Side& side : SidesOf(rect)) AddSegmentCircleIntersections(side, circle, out);
  } else {
    for (const Side& s : SidesOf(first.rect)) {
      for (const Side& t : SidesOf(second.rect)) AddSegmentIntersection(s, t, out);
    }
  }
}

}  // namespace

double Norm(Vec2 v) { return std::hypot(v.x, v.y); }
// Norm(b - a) without the call (a call through the library's symbol table).
double Distance(Vec2 a, Vec2 b) {
  const Vec2 d = b - a;
  return std::hypot(d.x, d.y);
}

Angle Bearing(Vec2 from, Vec2 to) {
  const Vec2 d = to - from;
  if (d.x == 0.0 && d.y == 0.0) return Angle(0.0);
  return Angle::FromRadians(std::atan2(d.y, d.x));
}

Vec2 UnitVector(Angle heading) {
  return {std::cos(heading.radians()), std::sin(heading.radians())};
}

double DistancePointSegment(Vec2 p, Vec2 a, Vec2 b) {
  return Distance(p, ClosestOnSegment(p, a, b));
}

Primitive Primitive::MakeCircle(Vec2 centre, double radius) {
  Primitive part;
  part.kind = Kind::kCircle;
  part.circle = {centre, radius};
  return part;
}

Primitive Primitive::MakeRect(Vec2 centre, Vec2 size) {
  Primitive part;
  part.kind = Kind::kRect;
  part.rect = {centre, size};
  return part;
}

Shape Shape::FromRect(Vec2 centre, Vec2 size) { return Shape({Primitive::MakeRect(centre, size)}); }

Shape Shape::FromCircle(Vec2 centre, double radius) {
  return Shape({Primitive::MakeCircle(centre, radius)});
}

bool Shape::Contains(Vec2 p) const {
  return std::any_of(parts_.begin(), parts_.end(),
                     [p](const Primitive& part) { return Depth(part, p) >= 0.0; });
}

double Shape::DistanceTo(Vec2 p) const {
  if (parts_.empty()) return kInfinity;
  return Distance(p, NearestPoint(p));
}

Vec2 Shape::NearestPoint(Vec2 p) const {
  // An empty shape has no point at all; p is the only answer that moves nothing.
  Vec2 best = p;
  double best_distance = kInfinity;
  for (const Primitive& part : parts_) {
    const Vec2 candidate = NearestPointOfPart(part, p);
    const double distance = Distance(p, candidate);
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

Vec2 Shape::NearestPointOutside(Vec2 p, double margin) const {
  if (!Contains(p)) return p;
  // Growing every part by the margin turns the task into finding the nearest point of the
  // grown union's border. That border is made of pieces of the parts' borders; the nearest
  // point of a piece is a foot of p on it or one of its ends (a corner or where two borders
  // cross). The bounding box adds points that are always outside, so there is an answer.
  std::vector<Primitive> grown;
  for (const Primitive& part : parts_) grown.push_back(Inflated(part, margin));
  std::vector<Vec2> candidates;
  for (std::size_t i = 0; i < grown.size(); ++i) {
    AddBorderPoints(grown[i], p, &candidates);
    for (std::size_t j = i + 1; j < grown.size(); ++j) {
      AddBorderIntersections(grown[i], grown[j], &candidates);
    }
  }
  Vec2 lo;
  Vec2 hi;
  BoundingBox(grown, &lo, &hi);
  AddBorderPoints(Primitive::MakeRect((lo + hi) * 0.5, hi - lo), p, &candidates);

  Vec2 best = p;
  double best_distance = kInfinity;
  for (const Vec2& q : candidates) {
    const double distance = Distance(p, q);
    const bool on_border = std::none_of(grown.begin(), grown.end(), [q](const Primitive& part) {
      return Depth(part, q) > kInsideTolerance;
    });
    if (distance < best_distance && on_border) {
      best = q;
      best_distance = distance;
    }
  }
  return best;
}

Vec2 Shape::Centre() const {
  if (parts_.empty()) return {};
  Vec2 lo;
  Vec2 hi;
  BoundingBox(parts_, &lo, &hi);
  return (lo + hi) * 0.5;
}

Shape Shape::Translated(Vec2 delta) const {
  std::vector<Primitive> moved = parts_;
  for (Primitive& part : moved) {
    part.circle.centre = part.circle.centre + delta;
    part.rect.centre = part.rect.centre + delta;
  }
  return Shape(std::move(moved));
}

bool Zone::Forbids(Vec2 p) const { return inverted != shape.Contains(p); }

Vec2 Zone::NearestAllowedPoint(Vec2 p, double margin) const {
  if (!Forbids(p)) return p;
  if (!inverted) return shape.NearestPointOutside(p, margin);
  // Aim for the part whose inset interior is nearest: the answer is `margin` inside the zone,
  // so a robot arriving there is not pushed straight back out by noise.
  Vec2 best = p;
  double best_distance = kInfinity;
  for (const Primitive& part : shape.parts()) {
    const Vec2 candidate = NearestInsetPointOfPart(part, p, margin);
    const double distance = Distance(p, candidate);
    if (distance < best_distance) {
      best = candidate;
      best_distance = distance;
    }
  }
  return best;
}

}  // namespace core
}  // namespace swarm_transport
