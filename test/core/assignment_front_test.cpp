// Leaders to the front slots (issue 27, item 6): PlanLeadersInFront, and the check of where the
// leaders stand when the transport begins (GatheringMetrics::LeadersBehind).
#include <gtest/gtest.h>

#include <vector>

#include "planner_fixture.h"
#include "swarm_transport/core/run_metrics_gathering.h"

namespace swarm_transport {
namespace core {
namespace {

using planner_fixture::Robot;
using planner_fixture::Round;
using planner_fixture::Target;

SelectionPlan Selection(const std::vector<PlannerRobot>& r, const std::vector<PlannerTarget>& t,
                        const SelectionParams& p) {
  return PlanSelection(r, t, p);
}

// Three slots in a row along x; the course points to -x (the front is the slot at x = 0).
std::vector<PlannerTarget> Row() { return {Target(0, 0), Target(1, 0), Target(2, 0)}; }

TEST(PlanLeadersInFrontTest, TheLeaderTakesTheFrontSlotEvenWhenItIsFarthest) {
  // Robot 2, the leader, stands behind the back slot; by the matrix alone it would take slot 2.
  const std::vector<PlannerRobot> robots = {Robot(0, 1, 0), Robot(1, 1, 0), Robot(2.5, 0, 180)};
  ASSERT_EQ(PlanSelection(robots, Row(), Round(0.0)).target_of[2], 2);
  const SelectionPlan plan = PlanLeadersInFront(robots, {false, false, true}, Row(), {1, 0},
                                                {-1, 0}, Round(0.0), Selection);
  EXPECT_EQ(plan.target_of, (std::vector<int>{1, 2, 0}));
  EXPECT_TRUE(plan.stable);
  EXPECT_DOUBLE_EQ(plan.time[2], 2.5);  // 2.5 m straight ahead at 1 m per unit
  EXPECT_DOUBLE_EQ(plan.total, plan.time[0] + plan.time[1] + plan.time[2]);
}

TEST(PlanLeadersInFrontTest, ARowAcrossTheCourseIsAllFront) {
  // Course +y: slots (0,1) and (1,1) are equally far ahead; the leader takes the nearer.
  const std::vector<PlannerTarget> slots = {Target(0, 0), Target(1, 0), Target(0, 1), Target(1, 1)};
  const std::vector<PlannerRobot> robots = {Robot(0, 0.1, 90), Robot(1.2, 1.5, 270)};
  const SelectionPlan plan =
      PlanLeadersInFront(robots, {false, true}, slots, {0.5, 0.5}, {0, 1}, Round(0.0), Selection);
  EXPECT_EQ(plan.target_of[1], 3);
  EXPECT_EQ(plan.target_of[0], 2);  // a front slot no leader took is free for the others
}

TEST(PlanLeadersInFrontTest, WithoutLeadersItIsThePlannersPlan) {
  const std::vector<PlannerRobot> robots = {Robot(0, 1, 0), Robot(1, 1, 0), Robot(2.5, 0, 180)};
  EXPECT_EQ(PlanLeadersInFront(robots, {false, false, false}, Row(), {1, 0}, {-1, 0}, Round(0.0),
                               Selection)
                .target_of,
            PlanSelection(robots, Row(), Round(0.0)).target_of);
}

Carry Transport(bool leader) {
  Carry c;
  c.transport = true;
  c.leader = leader;
  c.centre = {5, 5};
  c.target = {1, 5};  // the front is toward -x
  return c;
}

TEST(LeadersBehindTest, CountsTheRobotsAheadOfTheRearmostLeaderAtTransportStart) {
  GatheringMetrics m;
  EXPECT_FALSE(m.LeadersBehind(0.05).has_value());
  m.AddPosition(1, 10, Transport(true), {4.0, 5.0});    // 1 m ahead
  m.AddPosition(2, 10, Transport(true), {4.5, 5.0});    // 0.5 m ahead: the rearmost leader
  m.AddPosition(3, 10, Transport(false), {4.48, 5.0});  // 0.52: within the tolerance
  m.AddPosition(4, 10, Transport(false), {5.5, 5.0});
  ASSERT_TRUE(m.LeadersBehind(0.05).has_value());
  EXPECT_EQ(*m.LeadersBehind(0.05), 0u);
  EXPECT_EQ(*m.LeadersBehind(0.0), 1u);
  m.AddPosition(5, 10, Transport(false), {3.0, 5.0});  // ahead of every leader
  m.AddPosition(2, 11, Transport(true), {3.0, 5.0});   // later ticks do not count
  EXPECT_EQ(*m.LeadersBehind(0.05), 1u);
}

TEST(LeadersBehindTest, GatheringPositionsDoNotCount) {
  GatheringMetrics m;
  Carry gathering = Transport(true);
  gathering.transport = false;
  m.AddPosition(1, 1, gathering, {4.0, 5.0});
  m.AddPosition(2, 1, Transport(false), {4.0, 5.0});
  EXPECT_FALSE(m.LeadersBehind(0.05).has_value());  // no leader at transport start
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
