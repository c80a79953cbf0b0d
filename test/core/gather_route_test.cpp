// Gathering robots around danger zones (issue 27, item 7): a robot's own way to its goal, the
// way out of a zone it starts in, the waypoints it heads for, the planner's routed view of it,
// and a gathering robot that drives out of a cup-shaped zone and around it to its slot.
#include "swarm_transport/core/gather_route.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "fixtures.h"
#include "swarm_transport/core/mission_agent.h"
#include "swarm_transport/core/transport.h"

namespace swarm_transport {
namespace core {
namespace {

using fixtures::At;
using fixtures::Quiet;

constexpr auto Rect = fixtures::RectZone;
constexpr auto Clearance = fixtures::WithClearance;

// A cup open to the west at x 3.5..5.4, y 5.1..8.9: a gathering robot inside it whose object
// lies to the east would press against its bottom for good driving straight.
std::vector<Zone> Cup() {
  return {Rect(-1, 5.0, 5.1, 5.4, 8.9), Rect(-2, 3.5, 8.5, 5.4, 8.9), Rect(-3, 3.5, 5.1, 5.4, 5.5)};
}

bool InAny(const std::vector<Zone>& zones, Vec2 q) {
  for (const Zone& z : zones) {
    if (z.Forbids(q)) return true;
  }
  return false;
}

constexpr auto WayLength = fixtures::PolylineLength;

TEST(GatherRouteTest, NoWayWhenTheStraightLineIsClear) {
  const std::vector<Zone> zones = {Rect(-1, 8, 1, 9, 2)};
  GatherWay way = PlanGatherWay({2, 5}, {7, 5}, zones, Clearance(0.11));
  EXPECT_TRUE(way.waypoints.empty());
  EXPECT_FALSE(way.Next({2, 5}, zones, Clearance(0.11), 0.22));
  EXPECT_TRUE(PlanGatherWay({2, 5}, {7, 5}, {}, Clearance(0.11)).waypoints.empty());
  const PlannerRobot robot{{2, 5}, Angle(30.0)};
  const PlannerRobot seen = RoutedForPlanner(robot, {7, 5}, zones, Clearance(0.11));
  EXPECT_EQ(seen.position.x, 2.0);
  EXPECT_EQ(seen.position.y, 5.0);
  EXPECT_EQ(seen.extra_m, 0.0);
  EXPECT_EQ(seen.heading.degrees(), 30.0);
}

TEST(GatherRouteTest, OutOfTheCupAndAroundItEveryLegClear) {
  const std::vector<Zone> zones = Cup();
  const PathParams p = Clearance(0.11);
  const Vec2 from{4.5, 7.0};
  const Vec2 goal{7.0, 7.0};
  GatherWay way = PlanGatherWay(from, goal, zones, p);
  ASSERT_GE(way.waypoints.size(), 3u);
  EXPECT_NEAR(Distance(way.waypoints.back(), goal), 0.0, 1e-12);
  Vec2 at = from;
  for (const Vec2& w : way.waypoints) {
    EXPECT_TRUE(SegmentClear(at, w, zones, p)) << w.x << ", " << w.y;
    at = w;
  }
  // West out of the cup first (its mouth at x 3.5), then around an arm.
  EXPECT_LT(way.waypoints.front().x, 3.5);
  EXPECT_GT(WayLength(from, way.waypoints), 2.0 * Distance(from, goal));
  // Heads for the first corner; once beyond the last corner it sees its goal: none.
  const auto first = way.Next(from, zones, p, 0.22);
  ASSERT_TRUE(first);
  EXPECT_EQ(way.leg, 0u);
  const Vec2 last_corner = way.waypoints[way.waypoints.size() - 2];
  EXPECT_FALSE(way.Next(last_corner, zones, p, 0.22));
  EXPECT_EQ(way.leg, way.waypoints.size() - 1);
}

TEST(GatherRouteTest, ARobotInsideAZoneLeavesItByTheShortestWayFirst) {
  // A wall at x 5..6; the robot stands in it 0.2 m from its west side, its goal far east.
  const std::vector<Zone> zones = {Rect(-1, 5, 2, 6, 9)};
  const PathParams p = Clearance(0.11);
  const Vec2 from{5.2, 3.0};
  GatherWay way = PlanGatherWay(from, {8.0, 3.0}, zones, p);
  ASSERT_GE(way.waypoints.size(), 2u);
  const Vec2 out = way.waypoints.front();
  EXPECT_FALSE(InAny(zones, out));
  EXPECT_NEAR(out.x, 5.0 - 0.11, 1e-6);  // west: 0.2 m away, not east (0.8 m)
  EXPECT_NEAR(out.y, 3.0, 1e-6);
  for (std::size_t i = 1; i < way.waypoints.size(); ++i) {
    EXPECT_TRUE(SegmentClear(way.waypoints[i - 1], way.waypoints[i], zones, Clearance(0.0)));
  }
}

TEST(GatherRouteTest, ThePlannerSeesARoutedRobotAtItsLastCornerWithItsWayBefore) {
  const std::vector<Zone> zones = Cup();
  const PathParams p = Clearance(0.11);
  const PlannerRobot robot{{4.5, 7.0}, Angle(0.0)};
  const Vec2 goal{7.0, 7.0};
  const PlannerRobot seen = RoutedForPlanner(robot, goal, zones, p);
  const GatherWay way = PlanGatherWay(robot.position, goal, zones, p);
  // Its X counts the whole way: the way before the corner plus the corner's straight line.
  EXPECT_NEAR(seen.extra_m + Distance(seen.position, goal),
              WayLength(robot.position, way.waypoints), 1e-9);
  EXPECT_TRUE(SegmentClear(seen.position, goal, zones, p));
  // Against a robot in the open as far from the goal in a straight line: the routed one is
  // slower by its detour in the selection matrix.
  SelectionParams sp;
  const std::vector<PlannerTarget> targets = {{goal, 0.0}};
  const CostMatrix routed = SelectionMatrix({seen}, targets, sp);
  const CostMatrix straight = SelectionMatrix({robot}, targets, sp);
  EXPECT_GT(routed.at(0, 0), straight.at(0, 0) + 2.0 / sp.speed_m);
}

// Robot 1 of a two-robot mission (robot 0, its leader, stands under the object) gathers from
// inside the cup; it moves as CarryStep says, the cup a danger zone it may not enter.
struct CupRun {
  bool entered = false;
  bool routed = false;        // it got a waypoint
  std::uint64_t arrival = 0;  // first tick on its goal (0: never)
  double planned = -1.0;      // its X of the first plan (planned gathering)
};
CupRun GatherFromTheCup(GatherPlanner planner, bool with_zones) {
  MissionAgentParams params;
  params.transport.gather_planner = planner;
  if (with_zones) params.static_zones = Cup();
  MissionAgent agent(1, params);
  MissionSpec spec = fixtures::Thesis();  // object 2 x 2 at (7, 7)
  spec.range_to = 2;
  std::string why;
  EXPECT_TRUE(agent.OnNewMission(spec, &why)) << why;
  Perception in;
  in.self_id = 1;
  in.self = {{4.5, 7.0}, Angle(0.0)};
  in.others = {At(0, 7.5, 7.5)};
  in.zones = Cup();
  Rng rng(1, 1);
  CupRun run;
  for (std::uint64_t tick = 1; tick <= 300 && run.arrival == 0; ++tick) {
    const MissionPlan plan = agent.Tick(in.self, in.others, tick, nullptr);
    const Carry& carry = *plan.carry;
    if (run.planned < 0.0 && agent.last_gather_plan()) {
      run.planned = agent.last_gather_plan()->plan.time[1];
    }
    run.routed |= carry.via.has_value();
    const MoveDecision d = CarryStep(in, Quiet(), params.transport, carry, rng, 1.0);
    in.self.position = in.self.position + UnitVector(d.heading) * d.distance_m;
    in.self.heading = d.heading;
    run.entered |= InAny(Cup(), in.self.position);
    const Vec2 goal = carry.slot.value_or(carry.centre);
    if (Distance(in.self.position, goal) < 0.06) run.arrival = tick;
  }
  return run;
}

TEST(GatherRouteTest, AGatheringRobotLeavesTheCupAndReachesItsSlotNeverEnteringIt) {
  for (const GatherPlanner planner : {GatherPlanner::kSelectionMatrix, GatherPlanner::kNearest}) {
    SCOPED_TRACE(GatherPlannerName(planner));
    const CupRun run = GatherFromTheCup(planner, true);
    EXPECT_TRUE(run.routed);
    EXPECT_FALSE(run.entered);
    EXPECT_GT(run.arrival, 0u);
    if (planner == GatherPlanner::kSelectionMatrix) {
      // The plan's estimate counts the way around the cup (about 7 m): within a few ticks of
      // its arrival (65 against 69.3 ticks when written).
      EXPECT_GT(run.planned, 40.0);
      EXPECT_NEAR(static_cast<double>(run.arrival), run.planned, 5.0);
    }
  }
  // Not knowing the zones, it presses against the cup's bottom and never arrives.
  const CupRun blind = GatherFromTheCup(GatherPlanner::kSelectionMatrix, false);
  EXPECT_FALSE(blind.routed);
  EXPECT_FALSE(blind.entered);
  EXPECT_EQ(blind.arrival, 0u);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
