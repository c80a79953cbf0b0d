// The selection matrix [R3] and the optimal assignments it is compared with: hand-computed
// cases of the paper's figures and brute force on small random matrices.
#include "swarm_transport/core/assignment.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <set>

#include "planner_fixture.h"

namespace swarm_transport {
namespace core {
namespace {

using planner_fixture::Robot;
using planner_fixture::Target;
SelectionParams Round() { return planner_fixture::Round(0.5); }

TEST(SelectionMatrixTest, TimeIsDistanceOverSpeedPlusTurnOverTurnRate) {
  const std::vector<PlannerRobot> robots{Robot(0, 0, 0), Robot(0, 1, 0)};
  std::vector<PlannerTarget> targets{Target(2, 0), Target(2, 5)};
  targets[1].extra_m = 1.0;  // S_Bn
  const CostMatrix x = SelectionMatrix(robots, targets, Round());
  ASSERT_EQ(x.rows, 2u);
  ASSERT_EQ(x.cols, 2u);
  EXPECT_NEAR(x.at(0, 0), 2.0, 1e-9);  // straight ahead
  // sqrt(5) + atan(1/2) = 26.565 degrees / 90
  EXPECT_NEAR(x.at(1, 0), std::sqrt(5.0) + 26.56505118 / 90.0, 1e-6);
  // (sqrt(29) + 1) + atan(5/2) = 68.198590 degrees / 90
  EXPECT_NEAR(x.at(0, 1), std::sqrt(29.0) + 1.0 + 68.19859051 / 90.0, 1e-6);
  // (sqrt(20) + 1) + atan(4/2) = 63.434949 degrees / 90
  EXPECT_NEAR(x.at(1, 1), std::sqrt(20.0) + 1.0 + 63.43494882 / 90.0, 1e-6);
}

TEST(SelectionMatrixTest, TwoRobotsOneNearTargetGetOneTargetEach) {
  // The paper's fig. 5 / 6: both robots' own minimum is the same target; the global minimum
  // with its row and column removed (fig. 7) gives each robot its own.
  const std::vector<PlannerRobot> robots{Robot(0, 0, 0), Robot(0, 1, 0)};
  const std::vector<PlannerTarget> targets{Target(2, 0), Target(2, 5)};
  const CostMatrix x = SelectionMatrix(robots, targets, Round());
  for (std::size_t m = 0; m < 2; ++m) {
    EXPECT_LT(x.at(m, 0), x.at(m, 1)) << "robot " << m << " alone would pick target 0";
  }
  const Matching greedy = GreedyMinimum(x);
  EXPECT_EQ(greedy.target_of, (std::vector<int>{0, 1}));
  const SelectionPlan plan = PlanSelection(robots, targets, Round());
  EXPECT_EQ(plan.target_of, (std::vector<int>{0, 1}));
  EXPECT_TRUE(plan.stable);
  EXPECT_EQ(plan.rounds, 2);  // the second selection repeated the first
}

TEST(SelectionMatrixTest, GreedyTakesTheGlobalMinimumNotTheBestTotal) {
  CostMatrix x(2, 2);
  x.cost = {1, 2, 2, 100};
  EXPECT_EQ(GreedyMinimum(x).target_of, (std::vector<int>{0, 1}));
  EXPECT_DOUBLE_EQ(GreedyMinimum(x).total, 101.0);
  EXPECT_EQ(Hungarian(x).target_of, (std::vector<int>{1, 0}));
  EXPECT_DOUBLE_EQ(Hungarian(x).total, 4.0);
  EXPECT_DOUBLE_EQ(Bottleneck(x).last, 2.0);
}

TEST(SelectionMatrixTest, MoreRobotsThanTargetsLeavesTheSlowestWithout) {
  const std::vector<PlannerRobot> robots{Robot(0, 0, 0), Robot(5, 0, 0), Robot(1, 0, 0)};
  const std::vector<PlannerTarget> targets{Target(2, 0)};
  const SelectionPlan plan = PlanSelection(robots, targets, Round());
  EXPECT_EQ(plan.target_of, (std::vector<int>{-1, -1, 0}));
}

// Robot 0 at the origin heading east to (10, 0); robot 1 stands on that path.
SelectionPlan Blocked(double blocker_x, double robot_deg) {
  const std::vector<PlannerRobot> robots{Robot(0, 0, robot_deg), Robot(blocker_x, 0.2, 0)};
  const std::vector<PlannerTarget> targets{Target(10, 0)};
  const SelectionParams p = Round();
  SelectionPlan plan;
  plan.target_of = {0, -1};
  Corrections(robots, targets, SelectionMatrix(robots, targets, p), p, &plan);
  return plan;
}

TEST(SelectionCorrectionsTest, ABlockerOnThePathAddsT4) {
  // Robot 1 (no target) faces along the path: T2 = 90 degrees / 90 + 0.5 / 1 = 1.5. Robot 0
  // needs no turn (T1 = 0 <= T2) and reaches it at T3 = 1 <= T2: it waits T4 = 0.5.
  const SelectionPlan plan = Blocked(1.0, 0.0);
  EXPECT_NEAR(plan.blocked[0], 0.5, 1e-9);
  EXPECT_NEAR(plan.time[0], 10.0 + 0.5, 1e-9);
  EXPECT_DOUBLE_EQ(plan.blocked[1], 0.0);
  EXPECT_DOUBLE_EQ(plan.total, plan.time[0]);
}

TEST(SelectionCorrectionsTest, ABlockerFartherThanItsClearingTimeAddsNothing) {
  EXPECT_DOUBLE_EQ(Blocked(2.0, 0.0).blocked[0], 0.0);  // T3 = 2 > T2 = 1.5
  EXPECT_DOUBLE_EQ(Blocked(1.0, 0.0).crossing[0], 0.0);
}

TEST(SelectionCorrectionsTest, ARobotThatTurnsLongerThanTheBlockerIsNotBlocked) {
  // Robot 0 faces west: T1 = 180 / 90 = 2 > T2 = 1.5.
  EXPECT_DOUBLE_EQ(Blocked(1.0, 180.0).blocked[0], 0.0);
  // Facing north-east it turns 45 / 90 = 0.5 <= 1.5, reaches the blocker at 1.5 <= 1.5: T4 = 0.
  EXPECT_NEAR(Blocked(1.0, 45.0).blocked[0], 0.0, 1e-9);
  // Facing 30 degrees: T1 = 1/3, T3 = 4/3, T4 = 1.5 - 4/3 = 1/6.
  EXPECT_NEAR(Blocked(1.0, 30.0).blocked[0], 1.0 / 6.0, 1e-9);
}

TEST(SelectionCorrectionsTest, ARobotBesideThePathOrBehindDoesNotBlock) {
  const std::vector<PlannerRobot> robots{Robot(0, 0, 0), Robot(1, 0.6, 0), Robot(-1, 0, 0)};
  const std::vector<PlannerTarget> targets{Target(10, 0)};
  SelectionPlan plan;
  plan.target_of = {0, -1, -1};
  Corrections(robots, targets, SelectionMatrix(robots, targets, Round()), Round(), &plan);
  EXPECT_DOUBLE_EQ(plan.blocked[0], 0.0);
}

// Robot 0 from (-2, 0) east to (3, 0) (its goal 5 away), robot 1 from (0, -start) north to
// (0, goal_y): their paths cross at the origin.
SelectionPlan Crossing(double start, double goal_y = 1.0) {
  const std::vector<PlannerRobot> robots{Robot(-2, 0, 0), Robot(0, -start, 90)};
  const std::vector<PlannerTarget> targets{Target(3, 0), Target(0, goal_y)};
  const SelectionParams p = Round();
  SelectionPlan plan;
  plan.target_of = {0, 1};
  Corrections(robots, targets, SelectionMatrix(robots, targets, p), p, &plan);
  return plan;
}

TEST(SelectionCorrectionsTest, EqualArrivalAtACrossingDelaysTheRobotWhoseGoalIsFarther) {
  // Both reach the origin at t = 2; robot 0's goal is 5 away, robot 1's 3: robot 0 waits the
  // time the other needs to pass, 2 x 0.5 / 1 = 1.
  const SelectionPlan plan = Crossing(2.0);
  EXPECT_NEAR(plan.crossing[0], 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(plan.crossing[1], 0.0);
  EXPECT_NEAR(plan.time[0], 5.0 + 1.0, 1e-9);
  EXPECT_NEAR(plan.time[1], 3.0, 1e-9);
  EXPECT_NEAR(plan.last, 6.0, 1e-9);
  // Robot 1's goal at (0, 4) is 6 away, farther than robot 0's: robot 1 waits.
  const SelectionPlan other = Crossing(2.0, 4.0);
  EXPECT_DOUBLE_EQ(other.crossing[0], 0.0);
  EXPECT_NEAR(other.crossing[1], 1.0, 1e-9);
}

TEST(SelectionCorrectionsTest, ACrossingReachedAtDifferentTimesDelaysNobody) {
  // Robot 1 reaches the origin at 3, robot 0 at 2: 1 > the tolerance 0.5.
  EXPECT_DOUBLE_EQ(Crossing(3.0).crossing[0], 0.0);
  EXPECT_DOUBLE_EQ(Crossing(3.0).crossing[1], 0.0);
  // At 2.4 (|2 - 2.4| <= 0.5) they meet.
  EXPECT_NEAR(Crossing(2.4).crossing[0], 1.0, 1e-9);
  // Paths that do not cross (robot 1 stops short of the origin) delay nobody.
  EXPECT_DOUBLE_EQ(Crossing(2.0, -0.5).crossing[0], 0.0);
}

TEST(SelectionCorrectionsTest, TheSelectionIsRepeatedUntilItIsStable) {
  // Three robots, three slots, robot 1 on robot 0's way east: the plan ends stable within
  // max_rounds with one slot each and its total the sum of its times.
  const std::vector<PlannerRobot> robots{Robot(0, 0, 0), Robot(0.6, 0, 90), Robot(0, 2, 270)};
  const std::vector<PlannerTarget> targets{Target(1.5, 0), Target(0, -1), Target(1.5, 2)};
  const SelectionPlan plan = PlanSelection(robots, targets, Round());
  EXPECT_TRUE(plan.stable);
  EXPECT_LE(plan.rounds, Round().max_rounds);
  std::set<int> taken(plan.target_of.begin(), plan.target_of.end());
  EXPECT_EQ(taken.size(), 3u);
  double total = 0.0;
  for (double t : plan.time) total += t;
  EXPECT_NEAR(plan.total, total, 1e-9);
}

// Brute force: every injective map of the smaller side into the larger.
void BruteForce(const CostMatrix& m, double* best_total, double* best_last,
                double* total_at_best_last) {
  const bool wide = m.rows <= m.cols;
  const std::size_t small = wide ? m.rows : m.cols;
  const std::size_t large = wide ? m.cols : m.rows;
  std::vector<std::size_t> perm(large);
  std::iota(perm.begin(), perm.end(), 0);
  *best_total = std::numeric_limits<double>::infinity();
  *best_last = std::numeric_limits<double>::infinity();
  *total_at_best_last = std::numeric_limits<double>::infinity();
  do {
    double total = 0.0, last = 0.0;
    for (std::size_t k = 0; k < small; ++k) {
      const double c = wide ? m.at(k, perm[k]) : m.at(perm[k], k);
      total += c;
      last = std::max(last, c);
    }
    *best_total = std::min(*best_total, total);
    if (last < *best_last - 1e-12) {
      *best_last = last;
      *total_at_best_last = total;
    } else if (std::fabs(last - *best_last) <= 1e-12) {
      *total_at_best_last = std::min(*total_at_best_last, total);
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
}

void ExpectOneToOne(const Matching& got, const CostMatrix& m) {
  ASSERT_EQ(got.target_of.size(), m.rows);
  std::set<int> cols;
  std::size_t assigned = 0;
  for (int c : got.target_of) {
    if (c < 0) continue;
    ASSERT_LT(static_cast<std::size_t>(c), m.cols);
    cols.insert(c);
    ++assigned;
  }
  EXPECT_EQ(assigned, std::min(m.rows, m.cols));
  EXPECT_EQ(cols.size(), assigned);
}

TEST(OptimalAssignmentTest, HungarianAndBottleneckMatchBruteForceOnSmallRandomCases) {
  std::mt19937 gen(12345);
  std::uniform_int_distribution<int> size(1, 6);
  std::uniform_real_distribution<double> cost(0.0, 10.0);
  std::uniform_int_distribution<int> coarse(0, 4);  // ties
  for (int trial = 0; trial < 400; ++trial) {
    CostMatrix m(static_cast<std::size_t>(size(gen)), static_cast<std::size_t>(size(gen)));
    for (double& c : m.cost) c = trial % 2 ? cost(gen) : coarse(gen);
    double best_total, best_last, total_at_best_last;
    BruteForce(m, &best_total, &best_last, &total_at_best_last);
    const Matching h = Hungarian(m);
    const Matching b = Bottleneck(m);
    SCOPED_TRACE("trial " + std::to_string(trial));
    ExpectOneToOne(h, m);
    ExpectOneToOne(b, m);
    EXPECT_NEAR(h.total, best_total, 1e-9);
    EXPECT_NEAR(b.last, best_last, 1e-9);
    EXPECT_NEAR(b.total, total_at_best_last, 1e-9);
    const Matching g = GreedyMinimum(m);
    ExpectOneToOne(g, m);
    EXPECT_GE(g.total, best_total - 1e-9);
  }
}

TEST(OptimalAssignmentTest, PlanOptimalIsNeverWorseThanTheSelectionOnTheMatrix) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> coord(0.0, 10.0);
  std::uniform_real_distribution<double> deg(0.0, 360.0);
  for (int trial = 0; trial < 50; ++trial) {
    std::vector<PlannerRobot> robots;
    std::vector<PlannerTarget> targets;
    for (int k = 0; k < 6; ++k) robots.push_back(Robot(coord(gen), coord(gen), deg(gen)));
    for (int k = 0; k < 6; ++k) targets.push_back(Target(coord(gen), coord(gen)));
    const SelectionParams p = Round();
    const CostMatrix x = SelectionMatrix(robots, targets, p);
    const SelectionPlan hungarian = PlanOptimal(robots, targets, p, false);
    const SelectionPlan bottleneck = PlanOptimal(robots, targets, p, true);
    const SelectionPlan selection = PlanSelection(robots, targets, p);
    Matching h, b, s;
    h.target_of = hungarian.target_of;
    b.target_of = bottleneck.target_of;
    s.target_of = selection.target_of;
    double h_total = 0.0, s_total = 0.0, b_last = 0.0, s_last = 0.0;
    for (std::size_t m = 0; m < robots.size(); ++m) {
      h_total += x.at(m, static_cast<std::size_t>(h.target_of[m]));
      s_total += x.at(m, static_cast<std::size_t>(s.target_of[m]));
      b_last = std::max(b_last, x.at(m, static_cast<std::size_t>(b.target_of[m])));
      s_last = std::max(s_last, x.at(m, static_cast<std::size_t>(s.target_of[m])));
    }
    EXPECT_LE(h_total, s_total + 1e-9);
    EXPECT_LE(b_last, s_last + 1e-9);
  }
}

TEST(SelectionMatrixTest, GreedyGivesOneTargetEachEvenOnInfiniteCosts) {
  CostMatrix x(3, 3, std::numeric_limits<double>::infinity());
  x.at(2, 1) = 5.0;
  const Matching g = GreedyMinimum(x);
  EXPECT_EQ(g.target_of[2], 1);
  ExpectOneToOne(g, x);
}

TEST(OptimalAssignmentTest, EmptyMatricesAssignNothing) {
  EXPECT_TRUE(Hungarian(CostMatrix(0, 3)).target_of.empty());
  EXPECT_EQ(Bottleneck(CostMatrix(2, 0)).target_of, (std::vector<int>{-1, -1}));
  EXPECT_EQ(GreedyMinimum(CostMatrix(2, 0)).target_of, (std::vector<int>{-1, -1}));
}

TEST(AssignmentValidateTest, BadInputIsNamed) {
  EXPECT_EQ(Round().Validate(), "");
  SelectionParams p = Round();
  p.speed_m = 0.0;
  EXPECT_NE(p.Validate().find("speed"), std::string::npos);
  p = Round();
  p.turn_deg = -1.0;
  EXPECT_NE(p.Validate().find("turn"), std::string::npos);
  p = Round();
  p.max_rounds = 0;
  EXPECT_NE(p.Validate().find("max_rounds"), std::string::npos);
  p = Round();
  p.corridor_m = std::nan("");
  EXPECT_NE(p.Validate().find("corridor"), std::string::npos);
  CostMatrix m(2, 2);
  EXPECT_EQ(ValidateCostMatrix(m), "");
  m.cost[3] = std::numeric_limits<double>::infinity();
  EXPECT_NE(ValidateCostMatrix(m), "");
  m.cost.pop_back();
  EXPECT_NE(ValidateCostMatrix(m).find("3 entries"), std::string::npos);
}

MissionSpec CountOnly(std::uint16_t count) {
  MissionSpec m;
  m.id = 3;
  m.robot_count = count;
  m.leader_number = 1;
  m.object_centre = {7.0, 7.0};
  m.object_size = {2.0, 2.0};
  m.target = {3.0, 3.0};
  return m;
}

TEST(PickRobotsByCountTest, TheRobotsNearestTheObjectsSlotsAreTaken) {
  // Two slots nearest the centre of the 2 x 2 object (SlotsIn(2): 2 x 1 cells, at (6.5, 7)
  // and (7.5, 7)); robots 1 and 4 stand next to them, 0 and 9 far away.
  std::map<std::uint16_t, PlannerRobot> idle{
      {0, Robot(1, 1, 0)}, {1, Robot(5.5, 7, 0)}, {4, Robot(8.5, 7, 180)}, {9, Robot(10, 1, 90)}};
  MissionSpec spec = CountOnly(2);
  EXPECT_NE(ValidateMission(spec, MissionContext()).find("needs the mission dispatcher"),
            std::string::npos);
  ASSERT_EQ(PickRobotsByCount(&spec, idle, Round()), "");
  EXPECT_EQ(spec.robot_ids, (std::vector<std::uint16_t>{1, 4}));
  EXPECT_EQ(spec.robot_count, 0);
  EXPECT_EQ(spec.Leaders(), (std::vector<std::uint16_t>{1}));
  EXPECT_EQ(ValidateMission(spec, MissionContext()), "");  // a usual order now
}

TEST(PickRobotsByCountTest, BadCountsAreRefusedAndChangeNothing) {
  std::map<std::uint16_t, PlannerRobot> idle{{0, Robot(1, 1, 0)}, {1, Robot(2, 2, 0)}};
  MissionSpec spec = CountOnly(3);
  const MissionSpec before = spec;
  EXPECT_EQ(PickRobotsByCount(&spec, idle, Round()), "robot_count 3 but only 2 robots are idle");
  EXPECT_TRUE(spec.robot_ids.empty());
  EXPECT_EQ(spec.robot_count, before.robot_count);
  spec = CountOnly(1);
  spec.range_to = 2;  // a range besides the count
  EXPECT_NE(PickRobotsByCount(&spec, idle, Round()), "");
  EXPECT_NE(ValidateMission(spec, MissionContext()).find("besides a robot range"),
            std::string::npos);
  spec = CountOnly(1);
  spec.object_size = {0.0, 0.0};  // leader-only
  EXPECT_NE(PickRobotsByCount(&spec, idle, Round()).find("needs an object"), std::string::npos);
  EXPECT_TRUE(spec.robot_ids.empty());
  spec = CountOnly(0);
  EXPECT_NE(PickRobotsByCount(&spec, idle, Round()), "");
  // A candidate heard at no finite place is no candidate.
  idle[1] = Robot(std::nan(""), 2, 0);
  spec = CountOnly(2);
  EXPECT_EQ(PickRobotsByCount(&spec, idle, Round()), "robot_count 2 but only 1 robots are idle");
  spec = CountOnly(1);
  ASSERT_EQ(PickRobotsByCount(&spec, idle, Round()), "");
  EXPECT_EQ(spec.robot_ids, (std::vector<std::uint16_t>{0}));
}

// The leaders of a count-only mission are the picked robots at the front of the object on its
// course (issue 12), not the lowest ids: the 2 x 2 object at (7, 7) goes east to (10, 7); its 4
// slots are (6.5 | 7.5, 6.5 | 7.5). Robots 0 and 1 stand west of it (at the back), 2 and 3 east
// (at the front), each facing its nearest slot; robot 5 is far away.
std::map<std::uint16_t, PlannerRobot> BackAndFront() {
  return {{0, Robot(5.5, 6.5, 0)},
          {1, Robot(5.5, 7.5, 0)},
          {2, Robot(8.5, 6.5, 180)},
          {3, Robot(8.5, 7.5, 180)},
          {5, Robot(1, 10, 0)}};
}

MissionSpec EastBound(int leaders) {
  MissionSpec spec = CountOnly(4);
  spec.leader_number = leaders;
  spec.target = {10.0, 7.0};
  return spec;
}

TEST(PickRobotsByCountTest, TheLeadersAreTheRobotsAtTheFrontTowardTheTarget) {
  MissionSpec spec = EastBound(2);
  ASSERT_EQ(PickRobotsByCount(&spec, BackAndFront(), Round()), "");
  EXPECT_EQ(spec.robot_ids, (std::vector<std::uint16_t>{0, 1, 2, 3}));
  EXPECT_EQ(spec.leader_ids, (std::vector<std::uint16_t>{2, 3}));
  EXPECT_EQ(spec.Leaders(), (std::vector<std::uint16_t>{2, 3}));  // not the lowest, 0 and 1
  EXPECT_EQ(spec.FirstLeader(), 2);
  EXPECT_FALSE(spec.IsLeader(0));
  EXPECT_EQ(spec.LeadOrder(), (std::vector<std::uint16_t>{2, 3, 0, 1}));
  EXPECT_EQ(ValidateMission(spec, MissionContext()), "");
  // Westward the same robots pick the same slots, and 0 and 1 are at the front.
  spec = EastBound(2);
  spec.target = {2.0, 7.0};
  ASSERT_EQ(PickRobotsByCount(&spec, BackAndFront(), Round()), "");
  EXPECT_EQ(spec.leader_ids, (std::vector<std::uint16_t>{0, 1}));
  // Three leaders: the two front ones, then of the back ones the one whose slot lies ahead on a
  // course slightly north of east: robot 1 at y 7.5.
  spec = EastBound(3);
  spec.target = {10.0, 7.5};
  ASSERT_EQ(PickRobotsByCount(&spec, BackAndFront(), Round()), "");
  EXPECT_EQ(spec.leader_ids, (std::vector<std::uint16_t>{1, 2, 3}));
}

TEST(PickRobotsByCountTest, FrontTiesGoToTheShorterTimeThenTheLowerId) {
  // Due east, robots 2 and 3 are level at the front: the one with the shorter time X to its
  // slot leads - robot 3, 1 m from its slot, before robot 2, 1.5 m from its.
  std::map<std::uint16_t, PlannerRobot> idle = BackAndFront();
  idle[2] = Robot(9.0, 6.5, 180);
  MissionSpec spec = EastBound(1);
  ASSERT_EQ(PickRobotsByCount(&spec, idle, Round()), "");
  EXPECT_EQ(spec.leader_ids, (std::vector<std::uint16_t>{3}));
  // Level and equally far: the lower id.
  spec = EastBound(1);
  ASSERT_EQ(PickRobotsByCount(&spec, BackAndFront(), Round()), "");
  EXPECT_EQ(spec.leader_ids, (std::vector<std::uint16_t>{2}));
  // Target at the centre: no course, every slot level; the shortest time, then the lowest id.
  spec = EastBound(1);
  spec.target = spec.object_centre;
  ASSERT_EQ(PickRobotsByCount(&spec, idle, Round()), "");
  EXPECT_EQ(spec.leader_ids, (std::vector<std::uint16_t>{0}));
}

TEST(PickRobotsByCountTest, LeaderIdsAreTheDispatchersToName) {
  MissionSpec spec = EastBound(1);
  spec.leader_ids = {2};
  const std::string why = PickRobotsByCount(&spec, BackAndFront(), Round());
  EXPECT_NE(why.find("without leader_ids"), std::string::npos) << why;
  EXPECT_TRUE(spec.robot_ids.empty());
  // leader_number outside [1, robot_count]: no leaders named; the validation refuses the order.
  spec = EastBound(5);
  ASSERT_EQ(PickRobotsByCount(&spec, BackAndFront(), Round()), "");
  EXPECT_TRUE(spec.leader_ids.empty());
  EXPECT_NE(ValidateMission(spec, MissionContext()).find("larger than the group of 4"),
            std::string::npos);
}

TEST(SlotsInTest, SlotsSpreadOverTheObjectOnePerRobotAtLeast) {
  const Shape object = Shape::FromRect({7, 7}, {2, 2});
  const std::vector<Vec2> slots = SlotsIn(object, 20);
  ASSERT_EQ(slots.size(), 20u);  // 5 x 4 cells of 0.4 x 0.5
  for (const Vec2& s : slots) EXPECT_TRUE(object.Contains(s));
  EXPECT_NEAR(slots.front().x, 6.2, 1e-9);
  EXPECT_NEAR(slots.front().y, 6.25, 1e-9);
  for (std::size_t a = 0; a < slots.size(); ++a) {
    for (std::size_t b = a + 1; b < slots.size(); ++b) {
      EXPECT_GE(Distance(slots[a], slots[b]), 0.4 - 1e-9);
    }
  }
  EXPECT_EQ(SlotsIn(object, 15).size(), 16u);  // 4 x 4
  EXPECT_EQ(SlotsIn(object, 1).size(), 1u);
  EXPECT_NEAR(SlotsIn(object, 1).front().x, 7.0, 1e-9);
  EXPECT_TRUE(SlotsIn(object, 0).empty());
  EXPECT_TRUE(SlotsIn(Shape(), 5).empty());
}

TEST(SlotsInTest, ANeedleOfAnObjectGetsNoMoreCellsThanItsRobots) {
  // 10 m x 1 um: the square cells would be 3 x 1.7 million; at most 3 columns, one row.
  const std::vector<Vec2> slots = SlotsIn(Shape::FromRect({5, 5}, {10, 1e-6}), 3);
  ASSERT_EQ(slots.size(), 3u);
  EXPECT_NEAR(slots[0].x, 5.0 - 10.0 / 3.0, 1e-9);
  EXPECT_EQ(SlotsIn(Shape::FromRect({5, 5}, {1e-6, 10}), 3).size(), 3u);  // one column
}

TEST(SlotsInTest, AnLShapeGetsItsSlotsInside) {
  const Shape l({Primitive::MakeRect({1, 0.5}, {2, 1}), Primitive::MakeRect({0.5, 1.5}, {1, 1})});
  const std::vector<Vec2> slots = SlotsIn(l, 9);
  EXPECT_GE(slots.size(), 9u);
  for (const Vec2& s : slots) EXPECT_TRUE(l.Contains(s));
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
