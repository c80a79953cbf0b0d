// Assigning robots to targets [SPEC 9.10, R3]: the paper's selection matrix (time to reach each
// target, repeated global minimum, corrections for blockers on the path and crossing
// trajectories, repeated until stable) and, to compare it with, the optimal assignments
// (Hungarian: least total time; bottleneck: least last arrival). Pure.
#ifndef SWARM_TRANSPORT_CORE_ASSIGNMENT_H_
#define SWARM_TRANSPORT_CORE_ASSIGNMENT_H_

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "swarm_transport/core/angle.h"
#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/mission.h"

namespace swarm_transport {
namespace core {

// A cost matrix: rows (robots) x columns (targets), row-major.
struct CostMatrix {
  std::size_t rows = 0;
  std::size_t cols = 0;
  std::vector<double> cost;  // rows * cols finite values
  CostMatrix() = default;
  CostMatrix(std::size_t r, std::size_t c, double fill = 0.0)
      : rows(r), cols(c), cost(r * c, fill) {}
  double& at(std::size_t r, std::size_t c) { return cost[r * cols + c]; }
  double at(std::size_t r, std::size_t c) const { return cost[r * cols + c]; }
};

// One robot per target: target_of[r] is row r's column, or -1 when it has none (more robots
// than targets). min(rows, cols) rows get a column.
struct Matching {
  std::vector<int> target_of;
  double total = 0.0;  // sum of the chosen costs
  double last = 0.0;   // largest chosen cost (0 when nothing is chosen)
};

// The paper's selection [R3, fig. 7]: the global minimum of the matrix, then its row and column
// are removed, until rows or columns run out. Ties go to the lowest row, then column (and when
// every free cost is infinite, the first free pair).
Matching GreedyMinimum(const CostMatrix& m);
// One pair of a selection: a row (robot) and its column (target).
struct Pick {
  std::size_t row = 0;
  std::size_t col = 0;
  bool operator==(const Pick& o) const { return row == o.row && col == o.col; }
};
// GreedyMinimum with pairs given beforehand: the `fixed` pairs first (in their order; one whose
// row or column is out of range or already taken is skipped), their rows and columns removed,
// then the global minimum of the rest as GreedyMinimum. `order` (if not null) receives every
// pair taken, in the order taken (the fixed ones first).
Matching GreedyMinimumAfter(const CostMatrix& m, const std::vector<Pick>& fixed,
                            std::vector<Pick>* order);
// The paper's naive choice [R3, figs. 5-6]: each row its own minimum (ties: the lowest column),
// with no removal, so that several rows may get the same column.
Matching RowMinimum(const CostMatrix& m);
// Least total cost (Hungarian method with potentials, O(n^2 m)).
Matching Hungarian(const CostMatrix& m);
// Least largest cost; among those, the least total cost.
Matching Bottleneck(const CostMatrix& m);
// Empty when `m` is usable (sizes agree, every cost finite), else why not.
std::string ValidateCostMatrix(const CostMatrix& m);

// A robot as the planner sees it.
struct PlannerRobot {
  Vec2 position;
  Angle heading;
  // Its way before `position` (m): a robot routed around danger zones stands for the last
  // corner of its way (RoutedForPlanner, issue 27 item 7); 0 for a robot that drives straight.
  double extra_m = 0.0;
};

// A target: where, and the paper's per-target term S_Bn (m; the target robot's distance to the
// ring's edge in the paper, 0 for a slot under an object).
struct PlannerTarget {
  Vec2 position;
  double extra_m = 0.0;
};

// Parameters of the selection matrix. Times are in ticks when speeds are per tick.
struct SelectionParams {
  double speed_m = 0.1;    // V: distance per time unit
  double turn_deg = 90.0;  // VA: degrees turned per time unit
  // A robot whose centre lies within this distance of another's straight path blocks it
  // (2 robot radii plus the 10 % margin of the collision check: 0.11 for radius 0.05).
  double corridor_m = 0.11;
  // Two robots reach a crossing "at the same time" when their times differ by at most this;
  // the one whose goal is farther then waits `crossing_wait` (both: time units; <= 0 for the
  // wait: 2 * corridor_m / speed_m, the time the other needs to pass).
  double meet_tolerance = 1.0;
  double crossing_wait = 0.0;
  // T2 of a blocker that stands on its own target (it has no turn to make): the time it is
  // assumed to need to let the robot pass (time units; < 0: corridor_m / speed_m, the time to
  // cross a corridor's width - 1.1 ticks at 0.11 m and 0.1 m per tick).
  double settled_clear = -1.0;
  // Selections at most (the first included), >= 3; PlanSelection's freezing rule makes every
  // plan stable within them.
  int max_rounds = 8;
  // Empty when valid, else one sentence naming the first bad field.
  std::string Validate() const;
};

// The planner's result.
struct SelectionPlan {
  std::vector<int> target_of;    // per robot: its target index, or -1
  std::vector<double> time;      // per robot: estimated arrival with its corrections (0 if none)
  std::vector<double> blocked;   // per robot: T4, the waits for robots on its straight path
  std::vector<double> crossing;  // per robot: the waits at crossings
  double total = 0.0;            // sum of the assigned robots' times
  double last = 0.0;             // the latest of them
  int rounds = 0;                // selections made
  bool stable = false;           // the last selection repeated the one before
  std::size_t frozen = 0;        // pairs frozen by PlanSelection's rule when it ended
};

// X_mn = (S_mn + S_Bn + E_m) / V + ANG_mn / VA: S_mn the distance from robot m to target n,
// ANG_mn the angle (degrees, in [0, 180]) between robot m's heading and its bearing to target n,
// E_m robot m's extra_m (its way before its position when routed; 0 in the paper).
CostMatrix SelectionMatrix(const std::vector<PlannerRobot>& robots,
                           const std::vector<PlannerTarget>& targets, const SelectionParams& p);

// The waits of one assignment (target_of per robot, -1: unassigned; an unassigned robot still
// blocks the others' paths and turns away from them). Fills plan->blocked and plan->crossing.
//  - On the path [R3, figs. 9-10]: robot b within corridor_m of robot m's straight path (ahead
//    of m, before its target). T1 = m's turn time, T2 = b's time to clear the path (its turn
//    onto its own course - perpendicular to m's path when it has no target - plus corridor_m at
//    speed V; settled_clear when b stands on its own target). T3 = T1 + the distance along the
//    path to b / V (+ the waits for the robots before b); T3 > T2: b is gone. Else m waits
//    T4 = T2 - T3. (The paper also tests T1 > T2 first; T3 includes T1, so that test is
//    covered and not repeated. It writes T4 = T3 - T2, which under its own condition T3 <= T2
//    is never positive; the wait it describes is its magnitude.) Several robots on the path:
//    nearest first, each wait delaying m's arrival at the next.
//  - Crossings [R3, figs. 11-12]: where two assigned robots' straight paths cross, each one's
//    time to the crossing (turn + distance / V); when they differ by at most meet_tolerance the
//    robot whose goal is farther (ties: the higher index) waits crossing_wait.
void Corrections(const std::vector<PlannerRobot>& robots, const std::vector<PlannerTarget>& targets,
                 const CostMatrix& base, const SelectionParams& p, SelectionPlan* plan);

// The paper's planner: selection by repeated global minimum on X, corrections of the chosen
// pairs (their entries of the matrix become X + their waits), selection again on the corrected
// matrix, until the assignment repeats. The paper does not say that this ends; the corrections
// can make two selections alternate. So (issue 27) from the second selection on, every
// selection that changed the assignment freezes its first F unfrozen pairs, in the order the
// greedy took them: the next selections take the frozen pairs first and choose only among the
// remaining rows and columns. F = ceil(min(robots, targets) / (max_rounds - 2)). The unfrozen
// pairs decrease by F at every changed selection after the first two, so by selection
// max_rounds - 1 all are frozen and the next one repeats: every plan is stable within
// max_rounds (the first two selections are the paper's as they are; a plan stable after them
// is the paper's plan unchanged).
SelectionPlan PlanSelection(const std::vector<PlannerRobot>& robots,
                            const std::vector<PlannerTarget>& targets, const SelectionParams& p);

// The paper's naive baseline [R3, figs. 5-6]: each robot the target of its own row minimum of X
// (RowMinimum: no exclusion, several robots may share a target), times with the corrections.
SelectionPlan PlanRowMinimum(const std::vector<PlannerRobot>& robots,
                             const std::vector<PlannerTarget>& targets, const SelectionParams& p);

// The optimal assignments on the same matrix X (chosen without corrections): least total time
// (Hungarian) or least last arrival (bottleneck); times carry the corrections of the chosen
// assignment, like PlanSelection's, so that the two compare.
SelectionPlan PlanOptimal(const std::vector<PlannerRobot>& robots,
                          const std::vector<PlannerTarget>& targets, const SelectionParams& p,
                          bool bottleneck);

// (ext, issue 27, item 6) A plan whose leaders take the front slots: `is_leader` (per robot)
// marks the leaders; the front slots are the k slots furthest along `course` (k: the number of
// leaders; the projection of slot - `centre` onto `course`), widened by every slot as far along
// as the k-th (to 1e-9 m: a row across the course). `plan` assigns the leaders to the front
// slots, then the other robots to the slots left (each part is planned on its own: the robots
// of one part are not blockers in the other's corrections). The result is one plan over all
// robots and targets (indices as given; rounds the larger, stable when both are). Without a
// leader, or with fewer targets than robots, it is `plan` of all of them.
using Planner = std::function<SelectionPlan(
    const std::vector<PlannerRobot>&, const std::vector<PlannerTarget>&, const SelectionParams&)>;
SelectionPlan PlanLeadersInFront(const std::vector<PlannerRobot>& robots,
                                 const std::vector<bool>& is_leader,
                                 const std::vector<PlannerTarget>& targets, Vec2 centre,
                                 Vec2 course, const SelectionParams& p, const Planner& plan);

// Slots spread over `object` for `count` robots: the centres of the cells of a grid over its
// bounding box (cells as square as the box allows, cols x rows >= count) that lie inside it,
// the grid made finer until at least `count` do; all of them, row by row from the bottom.
// Empty when the object is empty or count is 0.
std::vector<Vec2> SlotsIn(const Shape& object, std::size_t count);

// (ext) A count-only transport mission (robot_count > 0, no range, no ids): its robots are the
// ones the selection matrix (PlanSelection) gives the robot_count slots of its object nearest
// the object's centre (of SlotsIn's), out of `idle` (the candidates: robots on no live mission,
// with their poses). On success it fills spec->robot_ids (ascending) and spec->leader_ids (the
// leader_number picked robots whose slots lie furthest toward the target: largest projection of
// slot - object centre onto target - object centre; ties by X, then by id; ascending; left empty
// when leader_number is outside [1, robot_count], which ValidateMission refuses) and sets
// robot_count to 0; else (also with leader_ids given) it returns why and changes nothing.
std::string PickRobotsByCount(MissionSpec* spec, const std::map<std::uint16_t, PlannerRobot>& idle,
                              const SelectionParams& p);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_ASSIGNMENT_H_
