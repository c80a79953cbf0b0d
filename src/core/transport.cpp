#include "swarm_transport/core/transport.h"

#include <algorithm>
#include <cmath>

#include "swarm_transport/core/problem.h"

namespace swarm_transport {
namespace core {
namespace {

// The avoidance search turns in whole degrees up to a step back [T5.2].
constexpr int kMaxSwerveDeg = 180;
// A formation robot this close to its place stands (nothing worth a move).
constexpr double kInPlaceM = 1e-6;
// Virtual copies are told apart by their one-byte sub_id.
constexpr int kMaxLeaderWeight = 255;

MoveDecision Drive(Angle desired, Angle heading, double distance, MoveOutcome outcome) {
  MoveDecision d;
  d.desired_heading = desired;
  d.heading = heading;
  d.distance_m = distance;
  d.outcome = outcome;
  return d;
}

// A passive robot in transport: the +-180 degree search for a heading whose point `lookahead`
// steps ahead lies inside the object and whose move is valid; slower after each failed search.
MoveDecision BoundedSearch(const Perception& in, const FlockingParams& p, const TransportParams& tp,
                           const Shape& object, Angle desired, double duration_s) {
  double speed = p.speed_m_per_tick;
  for (int attempt = 0; attempt <= tp.passive_tries; ++attempt) {
    for (int swerve = 0; swerve <= kMaxSwerveDeg; ++swerve) {
      for (const int sign : {1, -1}) {
        if (sign < 0 && (swerve == 0 || swerve == kMaxSwerveDeg)) continue;
        const Angle heading = desired + Angle(sign * swerve);
        // The cheap test first: most headings near a border fail it.
        const Vec2 ahead = in.self.position + UnitVector(heading) * (speed * tp.lookahead);
        if (!object.Contains(ahead) || !IsMoveValid(in, p, heading, speed, duration_s)) continue;
        const MoveOutcome outcome = attempt > 0  ? MoveOutcome::kSlowed
                                    : swerve > 0 ? MoveOutcome::kSwerved
                                                 : MoveOutcome::kStraight;
        return Drive(desired, heading, speed, outcome);
      }
    }
    speed *= tp.passive_slowdown;
  }
  return StandStill(desired, in.self.heading);
}

// A leader in transport: never swerves; slower on each blocked try; else turns and holds.
MoveDecision LeaderCarry(const Perception& in, const FlockingParams& p, const TransportParams& tp,
                         const Carry& carry, double duration_s) {
  const Angle steer = Bearing(carry.centre, carry.target);
  // Just outside (the object drifted off under it), it keeps to its course as long as that
  // takes it no farther out, so its heading still counts for the course in its swarm.
  const double out_before = carry.object.DistanceTo(in.self.position);
  double speed = p.speed_m_per_tick;
  for (int attempt = 0; attempt <= tp.leader_tries; ++attempt) {
    const Vec2 to = in.self.position + UnitVector(steer) * speed;
    const bool inside = !tp.leaders_bound || carry.object.DistanceTo(to) <= out_before;
    if (inside && IsMoveValid(in, p, steer, speed, duration_s)) {
      return Drive(steer, steer, speed,
                   attempt == 0 ? MoveOutcome::kStraight : MoveOutcome::kSlowed);
    }
    speed *= tp.leader_slowdown;
  }
  // It faces the course while it holds, so that its heading still counts for its swarm.
  return StandStill(steer, steer);
}

// Formation: every robot drives to its place in the body; the body moves along object centre
// -> target. The other members move by the same step this tick, so they are checked for
// collisions where they will be, not where they are.
MoveDecision FormationCarry(const Perception& in, const FlockingParams& p,
                            const TransportParams& tp, const Carry& carry, double duration_s) {
  const Vec2 to_target = carry.target - carry.centre;
  const double remaining = Norm(to_target);
  const double body_step = std::min(remaining, p.speed_m_per_tick * tp.formation_speed_fraction);
  const Vec2 step = remaining > 0.0 ? to_target * (body_step / remaining) : Vec2{};
  const Vec2 place = carry.centre + carry.formation_offset + step;
  const Vec2 at = in.self.position;
  // In place (within the slack a push apart by the simulator leaves): it moves exactly with the
  // body, and the other members, which do the same, are no obstacles to that move. Chasing the
  // last millimetres of its place would fight the push every tick.
  if (Distance(at + step, place) <= tp.formation_slack_m) {
    const double length = Norm(step);
    const Angle heading = length > kInPlaceM ? Bearing(at, at + step) : in.self.heading;
    if (length <= kInPlaceM) return StandStill(heading, in.self.heading);
    Perception others = in;
    others.others.erase(std::remove_if(others.others.begin(), others.others.end(),
                                       [&](const Neighbour& n) {
                                         return std::binary_search(carry.peers.begin(),
                                                                   carry.peers.end(), n.id);
                                       }),
                        others.others.end());
    if (IsMoveValid(others, p, heading, length, duration_s)) {
      return Drive(heading, heading, length, MoveOutcome::kStraight);
    }
  }
  // Out of place (or something else in its way): to its place at up to the full speed; the
  // members are checked where they will be after this tick's body step.
  const double gap = Distance(at, place);
  const Angle heading = Bearing(at, place);
  if (gap < kInPlaceM) return StandStill(heading, in.self.heading);
  Perception moved = in;
  for (Neighbour& n : moved.others) {
    if (std::binary_search(carry.peers.begin(), carry.peers.end(), n.id)) {
      n.position = n.position + step;
    }
  }
  FlockingParams reach = p;
  reach.speed_m_per_tick = std::min(gap, p.speed_m_per_tick);
  return AvoidCollisions(moved, reach, heading, duration_s);
}

// Gathering by a plan: straight for its own slot; around robots in the way (inside the object
// only onto moves that stay inside, so that it does not wall itself out); on it, it stands (a
// leader facing its course).
MoveDecision ToSlot(const Perception& in, const FlockingParams& p, const TransportParams& tp,
                    const Carry& carry, double duration_s) {
  const Vec2 position = in.self.position;
  const Angle course = Bearing(carry.centre, carry.target);
  const bool face = carry.leader && tp.leaders_face_course;
  if (face && carry.loading) return StandStill(course, course);
  const double gap = Distance(position, *carry.slot);
  const Angle toward = Bearing(position, *carry.slot);
  if (gap <= kInPlaceM)
    return face ? StandStill(course, course) : StandStill(toward, in.self.heading);
  FlockingParams reach = p;
  reach.speed_m_per_tick = std::min(gap, p.speed_m_per_tick);
  if (IsMoveValid(in, reach, toward, reach.speed_m_per_tick, duration_s)) {
    return Drive(toward, toward, reach.speed_m_per_tick, MoveOutcome::kStraight);
  }
  const MoveDecision d = AvoidCollisions(in, reach, toward, duration_s);
  const bool inside = carry.object.Contains(position);
  if (inside && d.distance_m > 0.0 &&
      !carry.object.Contains(position + UnitVector(d.heading) * d.distance_m)) {
    return face ? StandStill(course, course) : StandStill(toward, in.self.heading);
  }
  return d;
}

}  // namespace

bool ParseGatherMode(const std::string& name, GatherMode* out) {
  if (name == "hold") {
    *out = GatherMode::kHold;
  } else if (name == "fill") {
    *out = GatherMode::kFill;
  } else {
    return false;
  }
  return true;
}

bool ParseGatherPlanner(const std::string& name, GatherPlanner* out) {
  for (const GatherPlanner planner :
       {GatherPlanner::kNearest, GatherPlanner::kSelectionMatrix, GatherPlanner::kOptimal,
        GatherPlanner::kBottleneck, GatherPlanner::kRowMinimum}) {
    if (name == GatherPlannerName(planner)) {
      *out = planner;
      return true;
    }
  }
  return false;
}

const char* GatherPlannerName(GatherPlanner planner) {
  switch (planner) {
    case GatherPlanner::kSelectionMatrix:
      return "selection_matrix";
    case GatherPlanner::kOptimal:
      return "optimal";
    case GatherPlanner::kBottleneck:
      return "bottleneck";
    case GatherPlanner::kRowMinimum:
      return "row_minimum";
    default:
      return "nearest";
  }
}

std::string TransportParams::Validate() const {
  if (replan_period_ticks < 1) {
    return Problem("replan_period", ">= 1 (ticks)", replan_period_ticks);
  }
  if (!(planner_turn_deg_per_tick > 0.0) || !std::isfinite(planner_turn_deg_per_tick)) {
    return Problem("planner_turn_deg_per_tick", "finite and > 0", planner_turn_deg_per_tick);
  }
  if (!(lookahead >= 1.0) || !std::isfinite(lookahead)) {
    return Problem("transport lookahead", "finite and >= 1", lookahead);
  }
  if (!(passive_slowdown > 0.0 && passive_slowdown < 1.0)) {
    return Problem("passive_slowdown", "in (0, 1)", passive_slowdown);
  }
  if (passive_tries < 0) return Problem("passive_tries", ">= 0", passive_tries);
  if (!(leader_slowdown > 0.0 && leader_slowdown < 1.0)) {
    return Problem("leader_slowdown", "in (0, 1)", leader_slowdown);
  }
  if (leader_tries < 0) return Problem("leader_tries", ">= 0", leader_tries);
  if (transport_leader_weight < 1 || transport_leader_weight > kMaxLeaderWeight) {
    return Problem("transport_leader_weight", "in [1, 255]", transport_leader_weight);
  }
  if (!(leader_reach_m >= 0.0) || !std::isfinite(leader_reach_m)) {
    return Problem("leader_reach_m", "finite and >= 0", leader_reach_m);
  }
  if (!(approach_radius_m >= 0.0) || !std::isfinite(approach_radius_m)) {
    return Problem("approach_radius_m", "finite and >= 0", approach_radius_m);
  }
  if (!(formation_slack_m >= 0.0) || !std::isfinite(formation_slack_m)) {
    return Problem("formation_slack_m", "finite and >= 0", formation_slack_m);
  }
  if (!(formation_speed_fraction > 0.0 && formation_speed_fraction <= 1.0)) {
    return Problem("formation_speed_fraction", "in (0, 1]", formation_speed_fraction);
  }
  return "";
}

MoveDecision CarryStep(const Perception& in, const FlockingParams& p, const TransportParams& tp,
                       const Carry& carry, Rng& rng, double duration_s) {
  const Vec2 position = in.self.position;
  const bool passive_inside_transport = carry.transport && !carry.Arrived() &&
                                        carry.mode == TransportMode::kSwarm && !carry.leader &&
                                        carry.object.Contains(position);
  const bool routed = !carry.transport && carry.via.has_value();
  const bool to_slot = !carry.transport && carry.slot.has_value();
  const bool filling = !carry.transport && !routed && !to_slot && tp.gathering == GatherMode::kFill;
  if (!passive_inside_transport && !filling) {
    // The branches below use no free will: draw the sample the others draw.
    rng.Uniform(-p.free_will_deg / 2.0, p.free_will_deg / 2.0);
  }
  if (carry.Arrived()) return StandStill(in.self.heading, in.self.heading);
  if (carry.transport && carry.mode == TransportMode::kFormation) {
    return FormationCarry(in, p, tp, carry, duration_s);
  }
  // Around a danger zone: for its next waypoint (a move into the zone is never valid).
  if (routed) return AvoidCollisions(in, p, Bearing(position, *carry.via), duration_s);
  if (to_slot) return ToSlot(in, p, tp, carry, duration_s);
  const bool unbound_leader = carry.transport && carry.leader && !tp.leaders_bound;
  const bool near_leader =
      carry.transport && carry.leader && carry.object.DistanceTo(position) <= tp.leader_reach_m;
  if (!carry.object.Contains(position) && !unbound_leader && !near_leader && !filling) {
    return AvoidCollisions(in, p, Bearing(position, carry.centre), duration_s);
  }
  if (!carry.transport) {
    if (filling) {
      // Filling [T5.4]: the object is a safety zone to flee into and stay in.
      Perception kept = in;
      Zone safety;
      safety.shape = carry.object;
      safety.inverted = true;
      kept.zones.push_back(safety);
      return FlockingStep(kept, p, rng, duration_s);
    }
    const Angle course = Bearing(carry.centre, carry.target);
    const bool face = carry.leader && tp.leaders_face_course;
    if (face && carry.loading) return StandStill(course, course);
    // Hold: inside, it goes on straight for the centre while nothing is in its way and stands
    // once something is, so that robots do not wall off the rim against late-comers.
    const double to_centre = Distance(position, carry.centre);
    const Angle inward = Bearing(position, carry.centre);
    const double step = std::min(p.speed_m_per_tick, to_centre);
    if (step > kInPlaceM && IsMoveValid(in, p, inward, step, duration_s)) {
      return Drive(inward, inward, step, MoveOutcome::kStraight);
    }
    if (face) return StandStill(course, course);
    return StandStill(in.self.heading, in.self.heading);
  }
  FlockingParams approach = p;
  const double to_go = Distance(carry.centre, carry.target);
  if (to_go < tp.approach_radius_m) {
    approach.speed_m_per_tick = p.speed_m_per_tick * to_go / tp.approach_radius_m;
  }
  if (carry.leader) return LeaderCarry(in, approach, tp, carry, duration_s);
  bool fleeing = false;
  int neighbourhood_size = 0;
  // The leaders' virtual copies (stacking) for its alignment; collisions see only the robots.
  Perception weighted;
  if (tp.transport_leader_weight > 1) {
    weighted = StackLeaders(in, carry.leaders, tp.transport_leader_weight);
  }
  const Perception& aligned = tp.transport_leader_weight > 1 ? weighted : in;
  const Angle desired = DesiredHeading(aligned, p, rng, &fleeing, &neighbourhood_size);
  MoveDecision d = BoundedSearch(in, approach, tp, carry.object, desired, duration_s);
  d.fleeing = fleeing;
  d.neighbours_in_range = neighbourhood_size;
  return d;
}

}  // namespace core
}  // namespace swarm_transport
