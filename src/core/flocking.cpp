#include "swarm_transport/core/flocking.h"

#include <algorithm>
#include <cmath>

#include "swarm_transport/core/problem.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr std::uint8_t kTypePhysical = 0;
constexpr std::uint8_t kTypeVirtual = 1;
constexpr std::uint8_t kTypeStatist = 2;
// Closer than this the centroid gives no direction to turn to.
constexpr double kCentroidTolerance = 1e-9;
// Samples along a move's arc for the path check: the chords between them stray from an arc of
// one tick's length far less than a robot radius.
// The avoidance search turns in whole degrees up to a step back [T5.2].
constexpr int kMaxSwerveDeg = 180;

bool IsSelf(const Perception& in, const Neighbour& n) {
  return n.id == in.self_id && n.sub_id == 0 && n.type == kTypePhysical;
}

// Physical robots other than itself: the only ones a move can collide with.
bool IsOtherRobot(const Perception& in, const Neighbour& n) {
  return n.type == kTypePhysical && n.id != in.self_id;
}

// True when Distance(a, b) is certainly not greater than d (d >= 0), decided without a square
// root (FartherThan's other side): the squares' rounding error is far below the 1e-9 margin,
// and hypot is within an ulp of the exact distance, so whenever this says true the rounded
// Distance() is <= d too.
bool CertainlyWithin(Vec2 a, Vec2 b, double d) {
  return SquaredDistance(a, b) < d * d * (1.0 - 1e-9);
}

// How far `value` lies outside [lo, hi] (0 inside).
double Excess(double value, double lo, double hi) {
  return std::max({0.0, lo - value, value - hi});
}

// How far p is from being allowed by the zone: 0 when allowed.
double ZoneDepth(const Zone& zone, Vec2 p) { return Distance(p, zone.NearestAllowedPoint(p, 0.0)); }

}  // namespace

std::string FlockingParams::Validate() const {
  if (!std::isfinite(local_range_m) || local_range_m <= 0.0) {
    return Problem("local_range_m", "finite and > 0", local_range_m);
  }
  if (!(speed_m_per_tick > 0.0 && speed_m_per_tick < local_range_m)) {
    return Problem("speed_m_per_tick", "in (0, local_range_m)", speed_m_per_tick);
  }
  if (!(free_will_deg >= 0.0 && free_will_deg <= 360.0)) {
    return Problem("free_will_deg", "in [0, 360]", free_will_deg);
  }
  if (!(cohesion >= -1.0 && cohesion <= 1.0)) return Problem("cohesion", "in [-1, 1]", cohesion);
  if (!std::isfinite(robot_radius_m) || robot_radius_m <= 0.0) {
    return Problem("robot_radius_m", "finite and > 0", robot_radius_m);
  }
  if (!std::isfinite(collision_margin) || collision_margin < 0.0) {
    return Problem("collision_margin", "finite and >= 0", collision_margin);
  }
  if (!std::isfinite(world_size_m) || world_size_m <= 4.0 * robot_radius_m) {
    return Problem("world_size_m", "finite and > 4 * robot_radius_m", world_size_m);
  }
  if (!(speed_reduction > 0.0 && speed_reduction < 1.0)) {
    return Problem("speed_reduction", "in (0, 1)", speed_reduction);
  }
  if (speed_retries < 0) return Problem("speed_retries", ">= 0", speed_retries);
  if (!std::isfinite(zone_margin_m) || zone_margin_m < 0.0) {
    return Problem("zone_margin_m", "finite and >= 0", zone_margin_m);
  }
  return "";
}

bool ParseNeighbourhood(const std::string& name, Neighbourhood* out) {
  if (name == "chain") {
    *out = Neighbourhood::kChain;
  } else if (name == "disc") {
    *out = Neighbourhood::kDisc;
  } else {
    return false;
  }
  return true;
}

const char* NeighbourhoodName(Neighbourhood n) {
  return n == Neighbourhood::kChain ? "chain" : "disc";
}

bool FlockGroup::Admits(std::uint16_t id) const {
  return std::binary_search(ids.begin(), ids.end(), id) == only;
}

namespace {

// NeighbourhoodOf's and DesiredHeading's vectors, kept from call to call (per thread: a host's
// workers tick robots in parallel), so that a tick allocates none of them.
struct FlockingScratch {
  std::vector<Neighbour> neighbourhood;
  std::vector<const Neighbour*> candidates;
  std::vector<Vec2> frontier;
};

// Not inlined: a caller gets the thread's scratch once and passes it on. Inlined, the compiler
// specialised FillNeighbourhood for the thread-local lists and looked their address up (a call
// into the dynamic loader, the library being shared) at every use: 16 calls per robot tick.
__attribute__((noinline)) FlockingScratch* Scratch() {
  thread_local FlockingScratch scratch;
  return &scratch;
}

// NeighbourhoodOf into `neighbourhood` (emptied first), with `candidates` and `frontier` as its
// working lists.
void FillNeighbourhood(const Perception& in, const FlockingParams& p,
                       std::vector<Neighbour>* neighbourhood,
                       std::vector<const Neighbour*>* candidates_list,
                       std::vector<Vec2>* frontier_list) {
  Neighbour self;
  self.id = in.self_id;
  self.position = in.self.position;
  self.heading = in.self.heading;
  neighbourhood->clear();
  neighbourhood->reserve(in.others.size() + 1);
  neighbourhood->push_back(self);
  // Candidates not linked yet; statists join at once.
  std::vector<const Neighbour*>& candidates = *candidates_list;
  candidates.clear();
  candidates.reserve(in.others.size());
  for (const Neighbour& other : in.others) {
    // Its own echo would count it twice.
    if (IsSelf(in, other)) continue;
    if (other.type == kTypeStatist) {
      neighbourhood->push_back(other);
    } else if (in.group.Admits(other.id)) {
      candidates.push_back(&other);
    }
  }
  // Breadth first from itself: a disc stops after the first ring. Every robot linked so far is
  // tried once as the source of links to the rest (statists link nobody: they count, but a
  // chain runs through robots).
  std::vector<Vec2>& frontier = *frontier_list;
  frontier.clear();
  if (p.neighbourhood == Neighbourhood::kChain) frontier.reserve(candidates.size() + 1);
  frontier.push_back(in.self.position);
  for (std::size_t next = 0; next < frontier.size() && !candidates.empty(); ++next) {
    const Vec2 from = frontier[next];
    auto linked = std::partition(candidates.begin(), candidates.end(), [&](const Neighbour* n) {
      return FartherThan(from, n->position, p.local_range_m) ||
             (!CertainlyWithin(from, n->position, p.local_range_m) &&
              Distance(from, n->position) > p.local_range_m);
    });
    for (auto it = linked; it != candidates.end(); ++it) {
      const Neighbour& n = **it;
      neighbourhood->push_back(n);
      // A leader's announced copies stand where it stands: linked with it (SPEC 9.2).
      for (int k = 1; k <= n.copies; ++k) {
        Neighbour copy = n;
        copy.type = kTypeVirtual;
        copy.sub_id = static_cast<std::uint8_t>(k);
        copy.copies = 0;
        neighbourhood->push_back(copy);
      }
      if (p.neighbourhood == Neighbourhood::kChain) frontier.push_back(n.position);
    }
    candidates.erase(linked, candidates.end());
  }
}

}  // namespace

std::vector<Neighbour> NeighbourhoodOf(const Perception& in, const FlockingParams& p) {
  std::vector<Neighbour> neighbourhood;
  FlockingScratch* const scratch = Scratch();
  FillNeighbourhood(in, p, &neighbourhood, &scratch->candidates, &scratch->frontier);
  return neighbourhood;
}

int NeighbourhoodSize(const std::vector<Neighbour>& neighbourhood) {
  return static_cast<int>(std::count_if(neighbourhood.begin(), neighbourhood.end(),
                                        [](const Neighbour& n) { return n.type != kTypeVirtual; }));
}

Angle DesiredHeading(const Perception& in, const FlockingParams& p, Rng& rng, bool* fleeing,
                     int* neighbourhood_size) {
  const double free_will = rng.Uniform(-p.free_will_deg / 2.0, p.free_will_deg / 2.0);
  const Vec2 position = in.self.position;

  // Step 4 first: it overrides 1-3. Of the zones' escape points prefer one no zone forbids,
  // so that fleeing one zone does not lead straight into another.
  std::vector<Vec2> escapes;
  for (const Zone& zone : in.zones) {
    if (zone.Forbids(position)) {
      escapes.push_back(zone.NearestAllowedPoint(position, p.zone_margin_m));
    }
  }
  if (fleeing != nullptr) *fleeing = !escapes.empty();
  if (!escapes.empty()) {
    auto allowed = [&in](Vec2 q) {
      return std::none_of(in.zones.begin(), in.zones.end(),
                          [q](const Zone& zone) { return zone.Forbids(q); });
    };
    auto closer = [position](Vec2 a, Vec2 b) {
      return Distance(position, a) < Distance(position, b);
    };
    Vec2 target = *std::min_element(escapes.begin(), escapes.end(), closer);
    for (const Vec2& escape : escapes) {
      if (allowed(escape) && (!allowed(target) || closer(escape, target))) target = escape;
    }
    if (neighbourhood_size != nullptr) {
      *neighbourhood_size = NeighbourhoodSize(NeighbourhoodOf(in, p));
    }
    return Bearing(position, target);
  }

  FlockingScratch* const scratch = Scratch();
  const std::vector<Neighbour>& neighbourhood = scratch->neighbourhood;
  FillNeighbourhood(in, p, &scratch->neighbourhood, &scratch->candidates, &scratch->frontier);
  if (neighbourhood_size != nullptr) *neighbourhood_size = NeighbourhoodSize(neighbourhood);
  // CircularMean of the headings: the same sums in the same order, without their list.
  double sum_x = 0.0;
  double sum_y = 0.0;
  Vec2 sum;
  for (const Neighbour& n : neighbourhood) {
    sum = sum + n.position;
    // Statists stand still: they have a place but no heading to align with.
    if (n.type == kTypeStatist) continue;
    const double radians = n.heading.radians();
    sum_x += std::cos(radians);
    sum_y += std::sin(radians);
  }
  bool aligned = false;
  const Angle mean = CircularMeanOfSums(sum_x, sum_y, &aligned);
  // Cancelling headings leave every direction acceptable [T5.2]: keep going straight on.
  Angle heading = (aligned ? mean : in.self.heading) + Angle(free_will);

  const Vec2 centroid = sum * (1.0 / static_cast<double>(neighbourhood.size()));
  // FartherThan decides most without the square root; the rest as before.
  if (FartherThan(position, centroid, kCentroidTolerance) ||
      (!CertainlyWithin(position, centroid, kCentroidTolerance) &&
       Distance(position, centroid) > kCentroidTolerance)) {
    const Angle to_centroid = Bearing(position, centroid);
    heading = heading + Angle(p.cohesion * Angle::SignedDifference(to_centroid, heading));
  }
  return heading;
}

bool IsMoveValid(const Perception& in, const FlockingParams& p, Angle heading, double distance_m,
                 double duration_s) {
  const Pose2& start = in.self;
  const Velocity command = CommandFor(start, heading, distance_m, duration_s);
  const Vec2 from = start.position;
  const Vec2 to = TurnThenDrive(start, command, duration_s).position;

  // The arena border is an obstacle [T7.2]; a robot pushed beyond it may still come back.
  const double lo = p.robot_radius_m;
  const double hi = p.world_size_m - p.robot_radius_m;
  if (Excess(to.x, lo, hi) > Excess(from.x, lo, hi)) return false;
  if (Excess(to.y, lo, hi) > Excess(from.y, lo, hi)) return false;

  // Every robot counts here, not only those in range: a collision does not care about range.
  const double min_separation = p.MinSeparation();
  // Robots already closer than the separation (simultaneous moves, or a push by the
  // simulator) must not pin each other for good: with several of them around, as in a packed
  // corner, moving away from one means moving towards another. So a move is valid when it
  // comes too close to no new robot and strictly reduces the summed overlap with those that
  // already were too close.
  double overlap_before = 0.0;
  double overlap_after = 0.0;
  for (const Neighbour& other : in.others) {
    if (!IsOtherRobot(in, other)) continue;
    // Most neighbours are far from both ends: no square root for them (same decision).
    if (FartherThan(from, other.position, min_separation) &&
        FartherThan(to, other.position, min_separation)) {
      continue;
    }
    const double before = Distance(from, other.position);
    const double after = Distance(to, other.position);
    if (before >= min_separation) {
      if (after < min_separation) return false;
      continue;
    }
    overlap_before += min_separation - before;
    overlap_after += std::max(0.0, min_separation - after);
  }
  if (overlap_before > 0.0 && !(overlap_after < overlap_before)) return false;

  for (const Zone& zone : in.zones) {
    if (!zone.Forbids(to)) continue;
    if (!zone.Forbids(from) || ZoneDepth(zone, to) > ZoneDepth(zone, from)) return false;
  }

  if (!p.check_path) return true;
  // The path is the straight segment of the drive (the turn happens in place).
  const double touching = 2.0 * p.robot_radius_m;
  // A robot farther than touching + the drive from its start cannot be within touching of
  // any point of the drive. Most are farther than a bound above that reach (sqrt of the
  // squares, widened past their rounding and any underflow), so the exact reach's hypot is
  // needed only for the others (FartherThan grows with the distance it is given).
  const double reach_bound =
      touching + (std::sqrt(SquaredDistance(from, to)) * (1.0 + 1e-9) + 1e-150);
  double reach = -1.0;  // not computed yet
  for (const Neighbour& other : in.others) {
    if (FartherThan(from, other.position, reach_bound)) continue;
    if (reach < 0.0) reach = touching + Distance(from, to);
    if (FartherThan(from, other.position, reach)) continue;
    // A robot it is already closer to than the separation (touching after a push by the
    // simulator, rounded to float) would block every move: the overlap rule above already
    // decides how it may move relative to that one.
    if (!IsOtherRobot(in, other) || Distance(from, other.position) < min_separation) continue;
    if (DistancePointSegment(other.position, from, to) <= touching) return false;
  }
  return true;
}

MoveDecision AvoidCollisions(const Perception& in, const FlockingParams& p, Angle desired,
                             double duration_s) {
  MoveDecision decision;
  decision.desired_heading = desired;
  double speed = p.speed_m_per_tick;
  for (int attempt = 0; attempt <= p.speed_retries; ++attempt) {
    for (int swerve = 0; swerve <= kMaxSwerveDeg; ++swerve) {
      for (const int sign : {1, -1}) {
        // 0 and 180 have no distinct mirror image: try them once.
        if (sign < 0 && (swerve == 0 || swerve == kMaxSwerveDeg)) continue;
        const Angle heading = desired + Angle(sign * swerve);
        if (!IsMoveValid(in, p, heading, speed, duration_s)) continue;
        decision.heading = heading;
        decision.distance_m = speed;
        decision.outcome = attempt > 0  ? MoveOutcome::kSlowed
                           : swerve > 0 ? MoveOutcome::kSwerved
                                        : MoveOutcome::kStraight;
        return decision;
      }
    }
    speed *= p.speed_reduction;
  }
  decision.heading = in.self.heading;
  decision.distance_m = 0.0;
  decision.outcome = MoveOutcome::kStand;
  return decision;
}

MoveDecision FlockingStep(const Perception& in, const FlockingParams& p, Rng& rng,
                          double duration_s) {
  bool fleeing = false;
  int neighbourhood_size = 0;
  const Angle desired = DesiredHeading(in, p, rng, &fleeing, &neighbourhood_size);
  MoveDecision decision = AvoidCollisions(in, p, desired, duration_s);
  decision.fleeing = fleeing;
  decision.neighbours_in_range = neighbourhood_size;
  return decision;
}

Perception StackLeaders(const Perception& in, const std::vector<std::uint16_t>& leaders,
                        int weight) {
  Perception stacked = in;
  for (const Neighbour& n : in.others) {
    if (n.type != kTypePhysical || n.sub_id != 0 ||
        !std::binary_search(leaders.begin(), leaders.end(), n.id)) {
      continue;
    }
    for (int k = 1; k < weight; ++k) {
      Neighbour copy = n;
      copy.type = kTypeVirtual;
      copy.sub_id = static_cast<std::uint8_t>(k);
      stacked.others.push_back(copy);
    }
  }
  return stacked;
}

MoveDecision StandStill(Angle desired, Angle heading) {
  MoveDecision d;
  d.desired_heading = desired;
  d.heading = heading;
  d.distance_m = 0.0;
  d.outcome = MoveOutcome::kStand;
  return d;
}

}  // namespace core
}  // namespace swarm_transport
