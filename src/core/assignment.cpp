#include "swarm_transport/core/assignment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "swarm_transport/core/problem.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Shorter paths than this have no direction (the robot stands on its target).
constexpr double kNoPathM = 1e-9;
// Finer slot grids are tried up to this many times the robots' number of cells.
constexpr std::size_t kMaxSlotGridFactor = 64;

double Dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
double Cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }

double TurnTime(Angle heading, Angle course, const SelectionParams& p) {
  return std::fabs(Angle::SignedDifference(course, heading)) / p.turn_deg;
}

}  // namespace

std::string SelectionParams::Validate() const {
  if (!(speed_m > 0.0) || !std::isfinite(speed_m)) return Problem("planner speed", "> 0", speed_m);
  if (!(turn_deg > 0.0) || !std::isfinite(turn_deg)) {
    return Problem("planner turn rate", "> 0 (degrees per tick)", turn_deg);
  }
  if (!(corridor_m >= 0.0) || !std::isfinite(corridor_m)) {
    return Problem("planner corridor_m", ">= 0", corridor_m);
  }
  if (!(meet_tolerance >= 0.0) || !std::isfinite(meet_tolerance)) {
    return Problem("planner meet_tolerance", ">= 0", meet_tolerance);
  }
  if (!std::isfinite(crossing_wait))
    return Problem("planner crossing_wait", "finite", crossing_wait);
  if (!std::isfinite(settled_clear)) {
    return Problem("planner settled_clear", "finite (< 0: corridor_m / speed_m)", settled_clear);
  }
  if (max_rounds < 3) return Problem("planner max_rounds", ">= 3", max_rounds);
  return "";
}

CostMatrix SelectionMatrix(const std::vector<PlannerRobot>& robots,
                           const std::vector<PlannerTarget>& targets, const SelectionParams& p) {
  CostMatrix x(robots.size(), targets.size());
  for (std::size_t m = 0; m < robots.size(); ++m) {
    for (std::size_t n = 0; n < targets.size(); ++n) {
      const double s = Distance(robots[m].position, targets[n].position);
      const double turn =
          s > kNoPathM
              ? TurnTime(robots[m].heading, Bearing(robots[m].position, targets[n].position), p)
              : 0.0;
      x.at(m, n) = (s + targets[n].extra_m + robots[m].extra_m) / p.speed_m + turn;
    }
  }
  return x;
}

void Corrections(const std::vector<PlannerRobot>& robots, const std::vector<PlannerTarget>& targets,
                 const CostMatrix& base, const SelectionParams& p, SelectionPlan* plan) {
  const std::size_t count = robots.size();
  plan->blocked.assign(count, 0.0);
  plan->crossing.assign(count, 0.0);
  const auto goal = [&](std::size_t m) {
    return targets[static_cast<std::size_t>(plan->target_of[m])].position;
  };
  const auto assigned = [&](std::size_t m) { return plan->target_of[m] >= 0; };
  // The turn a robot makes before it drives (its T1).
  std::vector<double> turn(count, 0.0);
  for (std::size_t m = 0; m < count; ++m) {
    if (!assigned(m)) continue;
    const double length = Distance(robots[m].position, goal(m));
    if (length > kNoPathM) {
      turn[m] = TurnTime(robots[m].heading, Bearing(robots[m].position, goal(m)), p);
    }
  }
  // Robots on the straight path, nearest first: each waits until the one ahead cleared.
  for (std::size_t m = 0; m < count; ++m) {
    if (!assigned(m)) continue;
    const Vec2 from = robots[m].position;
    const double length = Distance(from, goal(m));
    if (length <= kNoPathM) continue;
    const Vec2 dir = (goal(m) - from) * (1.0 / length);
    std::vector<std::pair<double, std::size_t>> ahead;
    for (std::size_t b = 0; b < count; ++b) {
      if (b == m) continue;
      const Vec2 d = robots[b].position - from;
      const double along = Dot(d, dir);
      if (along <= 0.0 || along > length || std::fabs(Cross(dir, d)) >= p.corridor_m) continue;
      ahead.emplace_back(along, b);
    }
    std::sort(ahead.begin(), ahead.end());
    double delay = 0.0;
    for (const auto& [along, b] : ahead) {
      // The blocker's T2: its turn onto its own course (away across the path when it has
      // none), then a corridor's width at speed V.
      const double cross_corridor = p.corridor_m / p.speed_m;
      double t2 = cross_corridor;
      if (assigned(b) && Distance(robots[b].position, goal(b)) > kNoPathM) {
        t2 = turn[b] + cross_corridor;
      } else if (!assigned(b)) {
        const Angle path = Bearing(from, goal(m));
        t2 = std::min(TurnTime(robots[b].heading, path + Angle(90.0), p),
                      TurnTime(robots[b].heading, path + Angle(-90.0), p)) +
             cross_corridor;
      } else if (p.settled_clear >= 0.0) {
        t2 = p.settled_clear;  // on its own target
      }
      // The paper's first test, T1 > T2, is covered here: T3 >= T1.
      const double t3 = turn[m] + along / p.speed_m + delay;
      if (t3 > t2) continue;
      delay += t2 - t3;
    }
    plan->blocked[m] = delay;
  }
  // Crossing paths: equal times at the crossing delay the robot whose goal is farther.
  const double wait = p.crossing_wait > 0.0 ? p.crossing_wait : 2.0 * p.corridor_m / p.speed_m;
  for (std::size_t a = 0; a < count; ++a) {
    if (!assigned(a)) continue;
    for (std::size_t b = a + 1; b < count; ++b) {
      if (!assigned(b)) continue;
      const Vec2 pa = robots[a].position, ra = goal(a) - pa;
      const Vec2 pb = robots[b].position, rb = goal(b) - pb;
      const double denom = Cross(ra, rb);
      if (std::fabs(denom) < 1e-12) continue;  // parallel: the path rule covers robots ahead
      const double s = Cross(pb - pa, rb) / denom;
      const double t = Cross(pb - pa, ra) / denom;
      if (s < 0.0 || s > 1.0 || t < 0.0 || t > 1.0) continue;
      const double ta = turn[a] + s * Norm(ra) / p.speed_m + plan->blocked[a];
      const double tb = turn[b] + t * Norm(rb) / p.speed_m + plan->blocked[b];
      if (std::fabs(ta - tb) > p.meet_tolerance) continue;
      const std::size_t later = Norm(ra) > Norm(rb) ? a : b;  // ties: the higher index, b
      plan->crossing[later] += wait;
    }
  }
  plan->time.assign(count, 0.0);
  plan->total = 0.0;
  plan->last = 0.0;
  for (std::size_t m = 0; m < count; ++m) {
    if (!assigned(m)) continue;
    plan->time[m] = base.at(m, static_cast<std::size_t>(plan->target_of[m])) + plan->blocked[m] +
                    plan->crossing[m];
    plan->total += plan->time[m];
    plan->last = std::max(plan->last, plan->time[m]);
  }
}

SelectionPlan PlanSelection(const std::vector<PlannerRobot>& robots,
                            const std::vector<PlannerTarget>& targets, const SelectionParams& p) {
  SelectionPlan plan;
  const CostMatrix base = SelectionMatrix(robots, targets, p);
  CostMatrix corrected = base;
  std::vector<int> previous;
  std::vector<Pick> frozen, order;
  const std::size_t pairs = std::min(robots.size(), targets.size());
  const std::size_t freeze_rounds = static_cast<std::size_t>(std::max(1, p.max_rounds - 2));
  const std::size_t per_round = (pairs + freeze_rounds - 1) / freeze_rounds;  // F
  for (int round = 1; round <= p.max_rounds; ++round) {
    plan.target_of = GreedyMinimumAfter(corrected, frozen, &order).target_of;
    plan.rounds = round;
    Corrections(robots, targets, base, p, &plan);
    if (plan.target_of == previous) {
      plan.stable = true;
      break;
    }
    // The chosen pairs' entries carry their waits in the next selection.
    for (std::size_t m = 0; m < robots.size(); ++m) {
      if (plan.target_of[m] < 0) continue;
      const std::size_t n = static_cast<std::size_t>(plan.target_of[m]);
      corrected.at(m, n) = base.at(m, n) + plan.blocked[m] + plan.crossing[m];
    }
    // From the second selection on: its first F unfrozen pairs freeze (`order` begins with the
    // frozen ones).
    if (round >= 2) {
      const std::size_t upto = std::min(order.size(), frozen.size() + per_round);
      frozen.assign(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(upto));
    }
    previous = plan.target_of;
  }
  plan.frozen = frozen.size();
  return plan;
}

SelectionPlan PlanRowMinimum(const std::vector<PlannerRobot>& robots,
                             const std::vector<PlannerTarget>& targets, const SelectionParams& p) {
  SelectionPlan plan;
  const CostMatrix base = SelectionMatrix(robots, targets, p);
  plan.target_of = RowMinimum(base).target_of;
  plan.rounds = 1;
  plan.stable = true;
  Corrections(robots, targets, base, p, &plan);
  return plan;
}

SelectionPlan PlanOptimal(const std::vector<PlannerRobot>& robots,
                          const std::vector<PlannerTarget>& targets, const SelectionParams& p,
                          bool bottleneck) {
  SelectionPlan plan;
  const CostMatrix base = SelectionMatrix(robots, targets, p);
  plan.target_of = (bottleneck ? Bottleneck(base) : Hungarian(base)).target_of;
  plan.rounds = 1;
  plan.stable = true;
  Corrections(robots, targets, base, p, &plan);
  return plan;
}

std::string PickRobotsByCount(MissionSpec* spec, const std::map<std::uint16_t, PlannerRobot>& idle,
                              const SelectionParams& p) {
  std::ostringstream os;
  const std::size_t count = spec->robot_count;
  if (count == 0 || !spec->robot_ids.empty() || spec->range_from < spec->range_to) {
    os << "robot_count picks robots only for a mission with robot_count > 0 and no range or ids";
  } else if (!spec->leader_ids.empty()) {
    os << "robot_count " << count
       << " picks the leaders too: give it without leader_ids (the dispatcher names them)";
  } else if (spec->LeaderOnly()) {
    os << "robot_count needs an object (a leader-only mission names its leader)";
  } else if (!spec->all_finite) {
    os << "a field is not a finite number (NaN or inf)";
  }
  if (os.tellp() > 0) return os.str();
  // Candidates at a finite place only (a position message may carry anything).
  std::map<std::uint16_t, PlannerRobot> usable;
  for (const auto& kv : idle) {
    const PlannerRobot& r = kv.second;
    if (std::isfinite(r.position.x) && std::isfinite(r.position.y) &&
        std::isfinite(r.heading.degrees())) {
      usable.emplace(kv.first, r);
    }
  }
  if (count > usable.size()) {
    os << "robot_count " << count << " but only " << usable.size() << " robots are idle";
  }
  if (os.tellp() > 0) return os.str();
  const Vec2 centre = spec->object_centre;
  std::vector<Vec2> slots = SlotsIn(spec->ObjectAt(centre), count);
  if (slots.size() < count) return "the object has no room for " + std::to_string(count) + " slots";
  std::stable_sort(slots.begin(), slots.end(),
                   [&](Vec2 a, Vec2 b) { return Distance(a, centre) < Distance(b, centre); });
  slots.resize(count);
  std::vector<std::uint16_t> ids;
  std::vector<PlannerRobot> robots;
  for (const auto& kv : usable) {
    ids.push_back(kv.first);
    robots.push_back(kv.second);
  }
  std::vector<PlannerTarget> targets;
  for (const Vec2& s : slots) targets.push_back({s, 0.0});
  const SelectionPlan plan = PlanSelection(robots, targets, p);
  std::vector<std::uint16_t> picked;
  // The leaders: the picked robots whose slots lie furthest toward the target (the front of the
  // object on its course), ties (to 1e-9 m) by the matrix's time X, then by id.
  const CostMatrix x = SelectionMatrix(robots, targets, p);
  const Vec2 course = spec->target - centre;
  struct Front {
    double ahead;  // slot - centre projected onto the course, rounded to 1e-9
    double time;   // X of the robot to its slot
    std::uint16_t id;
  };
  std::vector<Front> front;
  for (std::size_t r = 0; r < ids.size(); ++r) {
    if (plan.target_of[r] < 0) continue;
    picked.push_back(ids[r]);
    const std::size_t n = static_cast<std::size_t>(plan.target_of[r]);
    const Vec2 off = slots[n] - centre;
    front.push_back(
        {std::round((off.x * course.x + off.y * course.y) * 1e9) / 1e9, x.at(r, n), ids[r]});
  }
  std::stable_sort(front.begin(), front.end(), [](const Front& a, const Front& b) {
    if (a.ahead != b.ahead) return a.ahead > b.ahead;
    if (a.time != b.time) return a.time < b.time;
    return a.id < b.id;
  });
  spec->robot_ids = picked;  // ascending: `usable` is ordered by id
  spec->robot_count = 0;
  // A leader_number outside [1, count] is left to ValidateMission (no leader_ids then).
  spec->leader_ids.clear();
  if (spec->leader_number >= 1 && static_cast<std::size_t>(spec->leader_number) <= front.size()) {
    for (int i = 0; i < spec->leader_number; ++i) spec->leader_ids.push_back(front[i].id);
    std::sort(spec->leader_ids.begin(), spec->leader_ids.end());
  }
  return "";
}

std::vector<Vec2> SlotsIn(const Shape& object, std::size_t count) {
  std::vector<Vec2> slots;
  if (object.empty() || count == 0) return slots;
  double x0 = kInf, y0 = kInf, x1 = -kInf, y1 = -kInf;
  for (const Primitive& part : object.parts()) {
    Vec2 lo, hi;
    if (part.kind == Primitive::Kind::kRect) {
      lo = part.rect.centre - part.rect.size * 0.5;
      hi = part.rect.centre + part.rect.size * 0.5;
    } else {
      lo = part.circle.centre - Vec2{part.circle.radius, part.circle.radius};
      hi = part.circle.centre + Vec2{part.circle.radius, part.circle.radius};
    }
    x0 = std::min(x0, lo.x);
    y0 = std::min(y0, lo.y);
    x1 = std::max(x1, hi.x);
    y1 = std::max(y1, hi.y);
  }
  const double w = x1 - x0, h = y1 - y0;
  if (!(w > 0.0) || !(h > 0.0)) return slots;
  for (std::size_t cells = count; cells <= count * kMaxSlotGridFactor; ++cells) {
    // Cells as square as the box allows, at most `cells` columns (a needle of an object must
    // not ask for billions of cells).
    double wide = std::ceil(std::sqrt(static_cast<double>(cells) * w / h));
    if (!(wide >= 1.0)) wide = 1.0;
    wide = std::min(wide, static_cast<double>(cells));
    const std::size_t cols = static_cast<std::size_t>(wide);
    const std::size_t rows = std::max<std::size_t>(1, (cells + cols - 1) / cols);
    slots.clear();
    for (std::size_t r = 0; r < rows; ++r) {
      for (std::size_t c = 0; c < cols; ++c) {
        const Vec2 centre{x0 + (static_cast<double>(c) + 0.5) * w / static_cast<double>(cols),
                          y0 + (static_cast<double>(r) + 0.5) * h / static_cast<double>(rows)};
        if (object.Contains(centre)) slots.push_back(centre);
      }
    }
    if (slots.size() >= count) return slots;
  }
  return slots;
}

}  // namespace core
}  // namespace swarm_transport
