#include "swarm_transport/core/balloon.h"

#include <algorithm>
#include <cmath>

#include "swarm_transport/core/problem.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr std::uint8_t kTypePhysical = 0;
// A push shorter than this (m) is no reason to move: the balloon sits in its balance.
constexpr double kStillM = 1e-3;
// Robots closer than this (m) give no direction: the push then points by the robot's id.
constexpr double kCoincidentM = 1e-9;
// A balloon swerves at most this far off its push: beyond it, the move would not take it off
// what it touches.
constexpr int kMaxBalloonSwerveDeg = 90;
// Two contact directions at least this close to 180 degrees apart leave a free side.
constexpr double kHalfTurnDeg = 180.0 - 1e-9;

}  // namespace

bool ParseStandbyMode(const std::string& name, StandbyMode* out) {
  if (name == "flock") {
    *out = StandbyMode::kFlock;
  } else if (name == "balloon") {
    *out = StandbyMode::kBalloon;
  } else {
    return false;
  }
  return true;
}

const char* StandbyModeName(StandbyMode mode) {
  return mode == StandbyMode::kBalloon ? "balloon" : "flock";
}

std::string BalloonParams::Validate() const {
  if (!std::isfinite(growth_m_per_tick) || !(growth_m_per_tick > 0.0)) {
    return Problem("balloon_growth_m_per_tick", "finite and > 0", growth_m_per_tick);
  }
  return "";
}

std::vector<BalloonContact> BalloonContacts(const Perception& in, const FlockingParams& p) {
  const double w = p.world_size_m;
  return BalloonContacts(in, p, Rect{{w / 2.0, w / 2.0}, {w, w}}, true);
}

std::vector<BalloonContact> BalloonContacts(const Perception& in, const FlockingParams& p,
                                            const Rect& borders, bool zones) {
  const Vec2 at = in.self.position;
  std::vector<BalloonContact> contacts;
  for (const Neighbour& other : in.others) {
    if (other.type != kTypePhysical || other.id == in.self_id) continue;
    if (FartherThan(at, other.position, p.local_range_m)) continue;
    const double d = Distance(at, other.position);
    BalloonContact c;
    c.distance_m = d / 2.0;
    c.away = d > kCoincidentM ? (at - other.position) * (1.0 / d)
                              : UnitVector(Angle(137.5 * in.self_id));
    contacts.push_back(c);
  }
  const Vec2 lo = borders.centre - borders.size * 0.5;
  const Vec2 hi = borders.centre + borders.size * 0.5;
  contacts.push_back({std::max(0.0, at.x - lo.x), {1.0, 0.0}});
  contacts.push_back({std::max(0.0, hi.x - at.x), {-1.0, 0.0}});
  contacts.push_back({std::max(0.0, at.y - lo.y), {0.0, 1.0}});
  contacts.push_back({std::max(0.0, hi.y - at.y), {0.0, -1.0}});
  for (const Zone& zone : in.zones) {
    if (!zones || zone.inverted || zone.shape.empty() || zone.Forbids(at)) continue;
    const Vec2 nearest = zone.shape.NearestPoint(at);
    const double d = Distance(at, nearest);
    if (d <= kCoincidentM) continue;
    contacts.push_back({d, (at - nearest) * (1.0 / d)});
  }
  std::stable_sort(
      contacts.begin(), contacts.end(),
      [](const BalloonContact& a, const BalloonContact& b) { return a.distance_m < b.distance_m; });
  return contacts;
}

bool BalloonEnclosed(const std::vector<BalloonContact>& contacts, double radius_m) {
  std::vector<double> toward;
  for (const BalloonContact& c : contacts) {
    if (c.distance_m > radius_m) continue;
    toward.push_back(Bearing({0.0, 0.0}, c.away * -1.0).degrees());
  }
  if (toward.size() < 3) return false;
  std::sort(toward.begin(), toward.end());
  double widest_gap = toward.front() + 360.0 - toward.back();
  for (std::size_t i = 1; i < toward.size(); ++i) {
    widest_gap = std::max(widest_gap, toward[i] - toward[i - 1]);
  }
  return widest_gap < kHalfTurnDeg;
}

double GrowBalloon(double radius_m, const std::vector<BalloonContact>& contacts,
                   const FlockingParams& p, const BalloonParams& bp) {
  double r = std::max(radius_m, p.robot_radius_m);
  if (!BalloonEnclosed(contacts, r)) r += bp.growth_m_per_tick;
  return std::clamp(r, p.robot_radius_m, std::max(p.robot_radius_m, p.local_range_m / 2.0));
}

Vec2 BalloonPush(const std::vector<BalloonContact>& contacts, double radius_m) {
  Vec2 push;
  for (const BalloonContact& c : contacts) {
    if (c.distance_m < radius_m) push = push + c.away * (radius_m - c.distance_m);
  }
  return push;
}

MoveDecision BalloonStep(const Perception& in, const FlockingParams& p, const BalloonParams& bp,
                         Rng& rng, double duration_s, double* radius_m) {
  const bool forbidden = std::any_of(in.zones.begin(), in.zones.end(),
                                     [&](const Zone& z) { return z.Forbids(in.self.position); });
  if (forbidden) return FlockingStep(in, p, rng, duration_s);
  // No free will in a balloon: draw the sample FlockingStep draws.
  rng.Uniform(-p.free_will_deg / 2.0, p.free_will_deg / 2.0);

  const std::vector<BalloonContact> contacts = BalloonContacts(in, p);
  *radius_m = GrowBalloon(*radius_m, contacts, p, bp);
  const Vec2 push = BalloonPush(contacts, *radius_m);
  const double length = Norm(push);
  const Angle along = length > 0.0 ? Bearing({0.0, 0.0}, push) : in.self.heading;
  MoveDecision d = StandStill(along, in.self.heading);
  if (length >= kStillM) {
    FlockingParams reach = p;
    reach.speed_m_per_tick = std::min(p.speed_m_per_tick, length);
    // Only the first search at full (push) speed and the slower retries, within +-90 degrees.
    const MoveDecision tried = AvoidCollisions(in, reach, along, duration_s);
    if (tried.distance_m > 0.0 &&
        std::abs(Angle::SignedDifference(tried.heading, along)) <= kMaxBalloonSwerveDeg) {
      d = tried;
    }
  }
  d.neighbours_in_range = NeighbourhoodSize(NeighbourhoodOf(in, p));
  return d;
}

bool ParseLoadingSpread(const std::string& name, LoadingSpread* out) {
  if (name == "none") {
    *out = LoadingSpread::kNone;
  } else if (name == "balloon") {
    *out = LoadingSpread::kBalloon;
  } else {
    return false;
  }
  return true;
}

const char* LoadingSpreadName(LoadingSpread spread) {
  return spread == LoadingSpread::kBalloon ? "balloon" : "none";
}

MoveDecision LoadingBalloonStep(const Perception& in, const FlockingParams& p,
                                const BalloonParams& bp, const Rect& object,
                                const std::vector<std::uint16_t>& peers, bool face, Angle course,
                                Rng& rng, double duration_s, double* radius_m) {
  // No free will under the object: draw the sample CarryStep draws.
  rng.Uniform(-p.free_will_deg / 2.0, p.free_will_deg / 2.0);
  Perception mine;
  mine.self_id = in.self_id;
  mine.self = in.self;
  for (const Neighbour& n : in.others) {
    if (std::binary_search(peers.begin(), peers.end(), n.id)) mine.others.push_back(n);
  }
  const std::vector<BalloonContact> contacts = BalloonContacts(mine, p, object, false);
  *radius_m = GrowBalloon(*radius_m, contacts, p, bp);
  const Vec2 push = BalloonPush(contacts, *radius_m);
  const double length = Norm(push);
  const Angle along = length > 0.0 ? Bearing({0.0, 0.0}, push) : in.self.heading;
  const Shape inside = Shape::FromRect(object.centre, object.size);
  MoveDecision d = StandStill(along, in.self.heading);
  if (length >= kStillM) {
    FlockingParams reach = p;
    reach.speed_m_per_tick = std::min(p.speed_m_per_tick, length);
    // Collisions against every robot heard; the move must end under the object.
    const MoveDecision tried = AvoidCollisions(in, reach, along, duration_s);
    if (tried.distance_m > 0.0 &&
        std::abs(Angle::SignedDifference(tried.heading, along)) <= kMaxBalloonSwerveDeg &&
        inside.Contains(in.self.position + UnitVector(tried.heading) * tried.distance_m)) {
      d = tried;
    }
  }
  if (d.distance_m == 0.0 && face) d.heading = course;
  d.neighbours_in_range = static_cast<int>(mine.others.size()) + 1;
  return d;
}

}  // namespace core
}  // namespace swarm_transport
