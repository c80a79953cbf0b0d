#include "swarm_transport/core/leader.h"

#include <algorithm>
#include <cmath>

#include "swarm_transport/core/problem.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr std::uint8_t kTypePhysical = 0;
// Steering this close to the goal's bearing means heading for the goal: do not overshoot it.
constexpr double kAtGoalBearingDeg = 1.0;

// The evaluated leader code's wait test (see LeaderParams::wait_evaluated_angles): its relative
// angle kept fmod's sign, and its "circular" normalisation turned a negative r into 360 - r
// (not 360 + r), so every centroid to the right of the course fell outside (90, 270).
bool EvaluatedCodeWaits(Angle to_centroid, Angle course) {
  const double bearing = Angle::SignedDifference(to_centroid, Angle(0));  // (-180, 180]
  double r = std::fmod(bearing - course.degrees(), 360.0);
  if (r < 0.0) r = 360.0 - r;
  return r > 90.0 && r < 270.0;
}

}  // namespace

std::string LeaderParams::Validate() const {
  if (!std::isfinite(goal_tolerance_m) || goal_tolerance_m <= 0.0) {
    return Problem("goal_tolerance_m", "finite and > 0", goal_tolerance_m);
  }
  if (!(wait_fraction > 0.0 && wait_fraction <= 1.0)) {
    return Problem("wait_fraction", "in (0, 1]", wait_fraction);
  }
  if (virtual_copies < 1 || virtual_copies > 255) {
    return Problem("leader_virtual_copies", "in [1, 255]", virtual_copies);
  }
  if (swerve_after_blocked_ticks < 0) {
    return Problem("leader_swerve_after_blocked_ticks", ">= 0", swerve_after_blocked_ticks);
  }
  return "";
}

LeaderDecision LeaderStep(const Perception& in, const FlockingParams& p, const LeaderParams& lp,
                          Vec2 goal, Angle steer, Rng& rng, double duration_s,
                          LeaderMemory* memory) {
  // A leader has no free will, but draws the sample FlockingStep would draw so that its random
  // sequence stays aligned when it changes role.
  rng.Uniform(-p.free_will_deg / 2.0, p.free_will_deg / 2.0);

  const std::vector<Neighbour> neighbourhood = NeighbourhoodOf(in, p);
  const Vec2 position = in.self.position;
  LeaderDecision decision;
  decision.move = StandStill(steer, in.self.heading);
  decision.move.neighbours_in_range = NeighbourhoodSize(neighbourhood);

  const double to_goal = Distance(position, goal);
  if (to_goal <= lp.goal_tolerance_m) {
    decision.arrived = true;
    return decision;
  }

  if (lp.keep_flock && !memory->gave_up) {
    Vec2 sum;
    int swarm_size = 0;
    for (const Neighbour& n : neighbourhood) {
      // Virtual copies and statists are not robots that could be left behind.
      if (n.type != kTypePhysical || n.id == in.self_id) continue;
      sum = sum + n.position;
      ++swarm_size;
    }
    if (swarm_size == 0) {
      // The swarm left its range entirely: waiting would not bring it back [T7.3].
      memory->gave_up = true;
    } else {
      const Vec2 centroid = lp.centroid_with_self ? (sum + position) * (1.0 / (swarm_size + 1))
                                                  : sum * (1.0 / swarm_size);
      const double to_centroid_m = Distance(position, centroid);
      if (lp.give_up_beyond_range && to_centroid_m > p.local_range_m) {
        // Its swarm's centre left its range entirely: it goes on alone [T7.3].
        memory->gave_up = true;
      } else {
        const bool far = to_centroid_m > lp.wait_fraction * p.local_range_m;
        const Angle to_centroid = Bearing(position, centroid);
        const bool behind =
            lp.wait_evaluated_angles
                ? EvaluatedCodeWaits(to_centroid, steer)
                : !lp.wait_behind || std::fabs(Angle::SignedDifference(to_centroid, steer)) > 90.0;
        if (far && behind) {
          ++memory->swarm_waits;
          return decision;
        }
      }
    }
  }

  const bool heading_for_goal =
      std::fabs(Angle::SignedDifference(steer, Bearing(position, goal))) <= kAtGoalBearingDeg;
  // Without its collision test the other robots are not in its way (the border and zones are).
  Perception alone;
  if (!lp.check_collisions) {
    alone.self_id = in.self_id;
    alone.self = in.self;
    alone.zones = in.zones;
  }
  const Perception& obstacles = lp.check_collisions ? in : alone;
  double speed = p.speed_m_per_tick;
  for (int attempt = 0; attempt <= p.speed_retries; ++attempt) {
    const double distance = heading_for_goal ? std::min(speed, to_goal) : speed;
    if (IsMoveValid(obstacles, p, steer, distance, duration_s)) {
      decision.move.heading = steer;
      decision.move.distance_m = distance;
      decision.move.outcome = attempt == 0 ? MoveOutcome::kStraight : MoveOutcome::kSlowed;
      memory->blocked_in_a_row = 0;
      return decision;
    }
    speed *= p.speed_reduction;
  }
  ++memory->blocked_waits;
  ++memory->blocked_in_a_row;
  if (lp.swerve_after_blocked_ticks > 0 &&
      memory->blocked_in_a_row > static_cast<std::uint64_t>(lp.swerve_after_blocked_ticks)) {
    // Blocked too long (another leader, a robot pinned against it): around it like any robot.
    const int neighbours = decision.move.neighbours_in_range;
    decision.move = AvoidCollisions(in, p, steer, duration_s);
    decision.move.neighbours_in_range = neighbours;
  }
  return decision;
}

}  // namespace core
}  // namespace swarm_transport
