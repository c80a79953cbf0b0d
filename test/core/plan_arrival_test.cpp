// The arithmetic of plan_arrival_error_ticks (issue 27, item 3) on made-up plans and positions.
#include "swarm_transport/core/plan_arrival.h"

#include <gtest/gtest.h>

#include <vector>

namespace swarm_transport {
namespace core {
namespace {

constexpr double kPlaced = 0.01;

TEST(PlanArrivalsTest, ErrorIsActualMinusPlannedArrival) {
  PlanArrivals a(kPlaced);
  a.Plan(1, 10, {1.0, 1.0}, 4.5);  // planned at 14.5
  a.Plan(2, 10, {2.0, 1.0}, 3.0);  // planned at 13
  for (std::uint64_t t = 10; t < 20; ++t) {
    a.At(1, t, t >= 17 ? Vec2{1.0, 1.005} : Vec2{0.0, 0.0});  // arrives at 17: 2.5 late
    a.At(2, t, t >= 12 ? Vec2{2.0, 1.0} : Vec2{0.0, 0.0});    // arrives at 12: 1 early
  }
  EXPECT_EQ(a.Errors(), (std::vector<double>{2.5, -1.0}));
  EXPECT_EQ(a.unarrived(), 0u);
  const ErrorSummary s = Summarize(a.Errors());
  EXPECT_DOUBLE_EQ(s.median_abs, 1.75);
  EXPECT_DOUBLE_EQ(s.max_abs, 2.5);
  EXPECT_DOUBLE_EQ(s.median, 0.75);
}

TEST(PlanArrivalsTest, AReplanKeepingTheSlotKeepsTheFirstEstimate) {
  PlanArrivals a(kPlaced);
  a.Plan(1, 0, {1.0, 1.0}, 5.0);
  a.Plan(1, 10, {1.0, 1.0}, 0.5);  // the same slot: still planned at 5
  a.At(1, 12, {1.0, 1.0});
  EXPECT_EQ(a.Errors(), (std::vector<double>{7.0}));
  EXPECT_EQ(a.slot_changes(), 0u);
}

TEST(PlanArrivalsTest, AnotherSlotStartsANewEstimateAndForgetsTheOldArrival) {
  PlanArrivals a(kPlaced);
  a.Plan(1, 0, {1.0, 1.0}, 3.0);
  a.At(1, 3, {1.0, 1.0});           // on its first slot at 3
  a.Plan(1, 10, {2.0, 1.0}, 10.0);  // moved to another: planned at 20
  EXPECT_TRUE(a.Errors().empty());
  EXPECT_EQ(a.unarrived(), 1u);
  EXPECT_EQ(a.slot_changes(), 1u);
  a.At(1, 21, {2.0, 1.0});
  EXPECT_EQ(a.Errors(), (std::vector<double>{1.0}));
  EXPECT_EQ(a.unarrived(), 0u);
}

TEST(PlanArrivalsTest, OnlyTheFirstTickOnTheSlotAtOrAfterThePlanCounts) {
  PlanArrivals a(kPlaced);
  a.At(1, 0, {1.0, 1.0});  // no plan yet: nothing
  a.Plan(1, 5, {1.0, 1.0}, 2.0);
  a.At(1, 4, {1.0, 1.0});   // before the plan's tick: ignored
  a.At(1, 6, {1.0, 1.02});  // 0.02 m off: not placed
  a.At(1, 8, {1.0, 1.0});   // arrives: 1 late
  a.At(1, 9, {3.0, 3.0});   // leaves and comes back later: the first arrival stays
  a.At(1, 30, {1.0, 1.0});
  EXPECT_EQ(a.Errors(), (std::vector<double>{1.0}));
}

TEST(PlanArrivalsTest, RobotsNeverOnTheirSlotAreCountedNotMeasured) {
  PlanArrivals a(kPlaced);
  a.Plan(1, 0, {1.0, 1.0}, 1.0);
  a.Plan(2, 0, {2.0, 2.0}, 1.0);
  a.At(2, 1, {2.0, 2.0});
  EXPECT_EQ(a.Errors(), (std::vector<double>{0.0}));
  EXPECT_EQ(a.unarrived(), 1u);
  EXPECT_TRUE(PlanArrivals(kPlaced).Errors().empty());
  const ErrorSummary none = Summarize({});
  EXPECT_EQ(none.median_abs, 0.0);
  EXPECT_EQ(none.max_abs, 0.0);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
