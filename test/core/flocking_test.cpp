#include "swarm_transport/core/flocking.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fixtures.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr double kTolerance = 1e-9;
constexpr double kTick = 1.0;

using fixtures::Quiet;
using fixtures::Robot;

// The perceiving robot.
constexpr auto At = fixtures::PerceptionAt;

// `count` robots evenly on a circle of `radius` around `centre`.
std::vector<Neighbour> Ring(Vec2 centre, double radius, int count) {
  std::vector<Neighbour> ring;
  for (int i = 0; i < count; ++i) {
    const Vec2 offset = UnitVector(Angle(360.0 * i / count)) * radius;
    ring.push_back(
        Robot(static_cast<std::uint16_t>(100 + i), centre.x + offset.x, centre.y + offset.y));
  }
  return ring;
}

// Where a move turning by `turn_deg` and driving `distance` from `in` ends.
Vec2 Destination(const Perception& in, double turn_deg, double distance) {
  const Angle heading = in.self.heading + Angle(turn_deg);
  return TurnThenDrive(in.self, CommandFor(in.self, heading, distance, kTick), kTick).position;
}

double Heading(Angle a) { return Angle::SignedDifference(a, Angle(0)); }

TEST(FlockingParamsTest, DefaultsAreValid) { EXPECT_EQ(FlockingParams().Validate(), ""); }

TEST(FlockingParamsTest, SpeedMustStayBelowRange) {
  FlockingParams p;
  p.speed_m_per_tick = 2.0;
  EXPECT_EQ(p.Validate(), "speed_m_per_tick must be in (0, local_range_m) but is 2");
}

TEST(FlockingParamsTest, RejectsNonFiniteAndOutOfRangeFields) {
  FlockingParams nan_range;
  nan_range.local_range_m = std::nan("");
  EXPECT_EQ(nan_range.Validate().rfind("local_range_m must be", 0), 0u);
  FlockingParams infinite_world;
  infinite_world.world_size_m = INFINITY;
  EXPECT_EQ(infinite_world.Validate().rfind("world_size_m must be", 0), 0u);
  FlockingParams cohesion;
  cohesion.cohesion = 1.5;
  EXPECT_EQ(cohesion.Validate(), "cohesion must be in [-1, 1] but is 1.5");
  FlockingParams reduction;
  reduction.speed_reduction = 1.0;
  EXPECT_EQ(reduction.Validate(), "speed_reduction must be in (0, 1) but is 1");
  FlockingParams tiny_world;
  tiny_world.world_size_m = 0.2;
  EXPECT_EQ(tiny_world.Validate().rfind("world_size_m must be", 0), 0u);
}

std::vector<int> SortedIds(const std::vector<Neighbour>& neighbourhood) {
  std::vector<int> ids;
  for (const Neighbour& n : neighbourhood) ids.push_back(n.id);
  std::sort(ids.begin(), ids.end());
  return ids;
}

TEST(NeighbourhoodTest, DiscHoldsSelfOnceRobotsInRangeAndEveryStatist) {
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(1, 5.0, 5.0),          // its own echo
               Robot(2, 5.9, 5.0),          // in range
               Robot(3, 6.1, 5.0),          // out of range (in range of 2: not for a disc)
               Robot(4, 10.0, 10.0, 0, 2),  // statist, far away
               Robot(5, 5.0, 6.0)};         // exactly at the range
  FlockingParams disc = Quiet();
  disc.neighbourhood = Neighbourhood::kDisc;
  const std::vector<Neighbour> neighbourhood = NeighbourhoodOf(in, disc);
  EXPECT_EQ(neighbourhood.front().id, 1);  // itself first, once
  EXPECT_EQ(SortedIds(neighbourhood), (std::vector<int>{1, 2, 4, 5}));
}

TEST(NeighbourhoodTest, ChainLinksRobotsHopByHopWithinRange) {
  // A line of robots 0.9 apart at range 1.0 is one swarm.
  Perception in = At(1.0, 5.0, 0.0);
  for (int i = 1; i <= 8; ++i) {
    in.others.push_back(Robot(static_cast<std::uint16_t>(1 + i), 1.0 + 0.9 * i, 5.0));
  }
  EXPECT_EQ(NeighbourhoodOf(in, Quiet()).size(), 9u);
  // A gap of 1.1 after the fourth robot splits it.
  for (std::size_t i = 4; i < in.others.size(); ++i) in.others[i].position.x += 0.2;
  EXPECT_EQ(SortedIds(NeighbourhoodOf(in, Quiet())), (std::vector<int>{1, 2, 3, 4, 5}));
  // The disc of the same robots holds only the first.
  FlockingParams disc = Quiet();
  disc.neighbourhood = Neighbourhood::kDisc;
  EXPECT_EQ(SortedIds(NeighbourhoodOf(in, disc)), (std::vector<int>{1, 2}));
}

TEST(NeighbourhoodTest, ChainRunsOnlyThroughTheRobotsItsGroupAdmits) {
  Perception in = At(1.0, 5.0, 0.0);
  in.others = {Robot(2, 1.9, 5.0), Robot(3, 2.8, 5.0), Robot(4, 3.7, 5.0), Robot(9, 1.0, 5.5)};
  // On a mission with 1, 2 and 4: 4 is linked only through 3, which is not in the group; 9 is
  // near but not in the group either.
  in.group.only = true;
  in.group.ids = {1, 2, 4};
  EXPECT_EQ(SortedIds(NeighbourhoodOf(in, Quiet())), (std::vector<int>{1, 2}));
  // Idle, with 3 on another robot's mission: 3 drops out and breaks the chain to 4.
  in.group.only = false;
  in.group.ids = {3};
  EXPECT_EQ(SortedIds(NeighbourhoodOf(in, Quiet())), (std::vector<int>{1, 2, 9}));
  // Idle, nobody excluded: everyone.
  in.group.ids.clear();
  EXPECT_EQ(SortedIds(NeighbourhoodOf(in, Quiet())), (std::vector<int>{1, 2, 3, 4, 9}));
}

TEST(NeighbourhoodTest, NamesParseBothWays) {
  Neighbourhood n = Neighbourhood::kDisc;
  ASSERT_TRUE(ParseNeighbourhood("chain", &n));
  EXPECT_EQ(n, Neighbourhood::kChain);
  EXPECT_STREQ(NeighbourhoodName(Neighbourhood::kDisc), "disc");
  EXPECT_FALSE(ParseNeighbourhood("ring", &n));
  EXPECT_EQ(n, Neighbourhood::kChain);
}

TEST(DesiredHeadingTest, AlignmentAloneAveragesHeadings) {
  // Thesis example: 45 and 315 average to 0 (its own heading 0 changes nothing).
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 5.3, 5.0, 45.0), Robot(3, 4.7, 5.0, 315.0)};
  Rng rng(1, 0);
  EXPECT_EQ(DesiredHeading(in, Quiet(), rng, nullptr), Angle(0));
}

TEST(DesiredHeadingTest, CancellingHeadingsKeepItsOwnHeading) {
  Perception in = At(5.0, 5.0, 90.0);
  in.others = {Robot(2, 5.3, 5.0, 270.0)};
  Rng rng(1, 0);
  EXPECT_EQ(DesiredHeading(in, Quiet(), rng, nullptr), Angle(90));
}

TEST(DesiredHeadingTest, StatistsDoNotVoteInAlignment) {
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(9, 5.0, 5.0, 90.0, 2)};  // on top of it, so no cohesion pull either
  Rng rng(1, 0);
  EXPECT_EQ(DesiredHeading(in, Quiet(), rng, nullptr), Angle(0));
}

TEST(DesiredHeadingTest, FreeWillStaysWithinHalfItsWidth) {
  FlockingParams p = Quiet();
  p.free_will_deg = 90.0;
  const Perception in = At(5.0, 5.0, 0.0);
  Rng rng(7, 3);
  double low = 180.0;
  double high = -180.0;
  for (int i = 0; i < 2000; ++i) {
    const double h = Heading(DesiredHeading(in, p, rng, nullptr));
    low = std::min(low, h);
    high = std::max(high, h);
  }
  EXPECT_GE(low, -45.0);
  EXPECT_LT(high, 45.0);
  EXPECT_LT(low, -40.0);
  EXPECT_GT(high, 40.0);
}

TEST(DesiredHeadingTest, DrawsExactlyOneSampleInEveryBranch) {
  FlockingParams p = Quiet();
  p.free_will_deg = 90.0;
  Perception calm = At(5.0, 5.0, 0.0);
  Perception fleeing = At(5.0, 5.0, 0.0);
  fleeing.zones = {Zone{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), false}};
  for (const Perception& in : {calm, fleeing}) {
    Rng rng(11, 2);
    Rng reference(11, 2);
    DesiredHeading(in, p, rng, nullptr);
    reference.Next();
    EXPECT_EQ(rng.Next(), reference.Next());
  }
}

TEST(DesiredHeadingTest, HalfCohesionTurnsHalfwayToTheCentroid) {
  // Centroid (5, 5.3) lies at 90; alignment gives 0; 0 + 0.5 * 90 = 45.
  FlockingParams p = Quiet();
  p.cohesion = 0.5;
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 5.0, 5.6, 0.0)};
  Rng rng(1, 0);
  EXPECT_EQ(DesiredHeading(in, p, rng, nullptr), Angle(45));
}

TEST(DesiredHeadingTest, NegativeCohesionTurnsAwayFromTheCentroid) {
  FlockingParams p = Quiet();
  p.cohesion = -0.5;
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 5.0, 5.6, 0.0)};
  Rng rng(1, 0);
  EXPECT_EQ(DesiredHeading(in, p, rng, nullptr), Angle(315));
}

TEST(DesiredHeadingTest, CohesionTurnsTheShortWay) {
  // The centroid lies at 270 = -90 from heading 0: half of it is -45, not half of 270.
  FlockingParams p = Quiet();
  p.cohesion = 0.5;
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 5.0, 4.4, 0.0)};
  Rng rng(1, 0);
  EXPECT_EQ(DesiredHeading(in, p, rng, nullptr), Angle(315));
}

TEST(DesiredHeadingTest, IgnoresRobotsOutOfRange) {
  FlockingParams p = Quiet();
  p.cohesion = 0.5;
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 5.0, 6.2, 90.0)};
  Rng rng(1, 0);
  EXPECT_EQ(DesiredHeading(in, p, rng, nullptr), Angle(0));
}

TEST(DesiredHeadingTest, FarStatistCountsInTheCentroid) {
  // Centroid of itself and the statist 4 m north is 2 m north: 0 + 0.5 * 90 = 45.
  FlockingParams p = Quiet();
  p.cohesion = 0.5;
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(9, 5.0, 9.0, 0.0, 2)};
  Rng rng(1, 0);
  EXPECT_EQ(DesiredHeading(in, p, rng, nullptr), Angle(45));
}

TEST(DesiredHeadingTest, FleesADangerZoneToTheNearestOutsidePoint) {
  // The top side (y = 6) is 0.4 away, the right side 0.7: flee north, ignoring free will,
  // alignment and cohesion.
  FlockingParams p = Quiet();
  p.free_will_deg = 90.0;
  p.cohesion = 0.5;
  Perception in = At(5.3, 5.6, 180.0);
  in.others = {Robot(2, 5.0, 5.0, 180.0)};
  in.zones = {Zone{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), false}};
  Rng rng(1, 0);
  bool fleeing = false;
  EXPECT_EQ(DesiredHeading(in, p, rng, &fleeing), Angle(90));
  EXPECT_TRUE(fleeing);
}

TEST(DesiredHeadingTest, FleesIntoItsSafetyZone) {
  // Nearest point 0.02 inside [4, 6]^2 from (2, 2) is (4.02, 4.02): bearing 45.
  FlockingParams p = Quiet();
  p.free_will_deg = 90.0;
  Perception in = At(2.0, 2.0, 270.0);
  in.zones = {Zone{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), true}};
  Rng rng(1, 0);
  bool fleeing = false;
  EXPECT_EQ(DesiredHeading(in, p, rng, &fleeing), Angle(45));
  EXPECT_TRUE(fleeing);
}

TEST(DesiredHeadingTest, DoesNotFleeInsideItsSafetyZone) {
  Perception in = At(5.0, 5.0, 30.0);
  in.zones = {Zone{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), true}};
  Rng rng(1, 0);
  bool fleeing = true;
  EXPECT_EQ(DesiredHeading(in, Quiet(), rng, &fleeing), Angle(30));
  EXPECT_FALSE(fleeing);
}

TEST(DesiredHeadingTest, FleesToAnEscapeNoOtherZoneForbids) {
  // Inside both [4, 6]^2 and the strip [5, 5.2] x [4, 6]. The strip's nearest way out (west,
  // 0.12 away) is inside the square; the square's (south, 0.52 away) is free: flee south.
  Perception in = At(5.1, 4.5, 0.0);
  in.zones = {Zone{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), false},
              Zone{2, Shape::FromRect({5.1, 5.0}, {0.2, 2.0}), false}};
  Rng rng(1, 0);
  EXPECT_EQ(DesiredHeading(in, Quiet(), rng, nullptr), Angle(270));
}

TEST(IsMoveValidTest, KeepsTheArenaBorderButMayComeBack) {
  const FlockingParams p = Quiet();
  // 0.0 is 0.05 outside the band [radius, world - radius]; 0.03 is still 0.02 outside.
  EXPECT_TRUE(IsMoveValid(At(0.0, 5.0, 0.0), p, Angle(0), 0.03, kTick));
  EXPECT_FALSE(IsMoveValid(At(0.03, 5.0, 180.0), p, Angle(180), 0.01, kTick));
  EXPECT_FALSE(IsMoveValid(At(0.1, 5.0, 180.0), p, Angle(180), 0.1, kTick));
  EXPECT_FALSE(IsMoveValid(At(5.0, 11.0, 90.0), p, Angle(90), 0.1, kTick));
}

TEST(IsMoveValidTest, RobotsTooCloseMayOnlyMoveApart) {
  const FlockingParams p = Quiet();
  Perception forward = At(5.0, 5.0, 0.0);
  forward.others = {Robot(2, 5.08, 5.0)};  // 0.08 < MinSeparation() = 0.11
  EXPECT_FALSE(IsMoveValid(forward, p, Angle(0), 0.01, kTick));
  Perception back = At(5.0, 5.0, 180.0);
  back.others = forward.others;
  EXPECT_TRUE(IsMoveValid(back, p, Angle(180), 0.01, kTick));
}

TEST(IsMoveValidTest, DestinationKeepsMinSeparationFromEveryRobot) {
  const FlockingParams p = Quiet();
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 5.2, 5.0)};
  EXPECT_FALSE(IsMoveValid(in, p, Angle(0), 0.1, kTick));  // 0.1 from it
  EXPECT_TRUE(IsMoveValid(in, p, Angle(0), 0.08, kTick));  // 0.12 from it
  in.others = {Robot(2, 5.2, 5.0, 0.0, 2)};                // a statist is not an obstacle
  EXPECT_TRUE(IsMoveValid(in, p, Angle(0), 0.1, kTick));
}

TEST(IsMoveValidTest, InsideAZoneMayOnlyMoveOut) {
  const FlockingParams p = Quiet();
  const Zone danger{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), false};
  Perception out = At(5.0, 5.5, 90.0);
  out.zones = {danger};
  EXPECT_TRUE(IsMoveValid(out, p, Angle(90), 0.1, kTick));
  Perception deeper = At(5.0, 5.5, 270.0);
  deeper.zones = {danger};
  EXPECT_FALSE(IsMoveValid(deeper, p, Angle(270), 0.1, kTick));
  Perception entering = At(5.0, 6.05, 270.0);
  entering.zones = {danger};
  EXPECT_FALSE(IsMoveValid(entering, p, Angle(270), 0.1, kTick));
}

TEST(IsMoveValidTest, PathCheckRejectsDrivingThroughARobot) {
  FlockingParams p = Quiet();
  p.speed_m_per_tick = 0.4;
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 5.2, 5.0)};  // the destination (5.4, 5) is 0.2 from it, the path 0
  EXPECT_FALSE(IsMoveValid(in, p, Angle(0), 0.4, kTick));
  p.check_path = false;
  EXPECT_TRUE(IsMoveValid(in, p, Angle(0), 0.4, kTick));
}

TEST(AvoidCollisionsTest, FreeWayGoesStraight) {
  const MoveDecision d = AvoidCollisions(At(5.0, 5.0, 0.0), Quiet(), Angle(30), kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kStraight);
  EXPECT_EQ(d.heading, Angle(30));
  EXPECT_EQ(d.desired_heading, Angle(30));
  EXPECT_NEAR(d.distance_m, 0.1, kTolerance);
}

TEST(AvoidCollisionsTest, TriesPlusBeforeMinus) {
  // A thin danger strip covers the destinations of 0, +1 and -1 degrees (|y - 5| <= 0.0026,
  // 0.1 sin 1 = 0.00175) but not those of +-2 (0.1 sin 2 = 0.0035): +2 comes first.
  Perception in = At(5.0, 5.0, 0.0);
  in.zones = {Zone{1, Shape::FromRect({5.1, 5.0}, {0.05, 0.0052}), false}};
  const MoveDecision d = AvoidCollisions(in, Quiet(), Angle(0), kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kSwerved);
  EXPECT_EQ(d.heading, Angle(2));
}

TEST(AvoidCollisionsTest, SearchesUntilTheOnlyFreeHeading) {
  // The safety zone allows only its own spot and a small box around the -3 degree destination.
  Perception in = At(5.0, 5.0, 0.0);
  const Vec2 target = Destination(in, -3.0, 0.1);
  in.zones = {Zone{1,
                   Shape({Primitive::MakeRect({5.0, 5.0}, {0.02, 0.02}),
                          Primitive::MakeRect(target, {0.01, 0.0016})}),
                   true}};
  const MoveDecision d = AvoidCollisions(in, Quiet(), Angle(0), kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kSwerved);
  EXPECT_EQ(d.heading, Angle(357));
  EXPECT_NEAR(d.distance_m, 0.1, kTolerance);
}

TEST(AvoidCollisionsTest, SlowsDownWhenEveryFullSpeedMoveCollides) {
  // A ring at 0.17: every full-speed destination (0.064 to 0.1 out) comes within 0.11 of it,
  // every half-speed one (<= 0.05 out) stays 0.12 away.
  Perception in = At(5.0, 5.0, 0.0);
  in.others = Ring({5.0, 5.0}, 0.17, 72);
  const MoveDecision d = AvoidCollisions(in, Quiet(), Angle(0), kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kSlowed);
  EXPECT_EQ(d.heading, Angle(0));
  EXPECT_NEAR(d.distance_m, 0.05, kTolerance);
}

TEST(AvoidCollisionsTest, StandsWhenBoxedIn) {
  Perception in = At(5.0, 5.0, 30.0);
  in.others = Ring({5.0, 5.0}, 0.12, 72);
  const MoveDecision d = AvoidCollisions(in, Quiet(), Angle(0), kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kStand);
  EXPECT_EQ(d.heading, Angle(30));
  EXPECT_EQ(d.desired_heading, Angle(0));
  EXPECT_EQ(d.distance_m, 0.0);
}

TEST(AvoidCollisionsTest, SwervesAlongTheArenaBorder) {
  const Perception in = At(0.1, 5.0, 180.0);
  const MoveDecision d = AvoidCollisions(in, Quiet(), Angle(180), kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kSwerved);
  const Vec2 end =
      TurnThenDrive(in.self, CommandFor(in.self, d.heading, d.distance_m, kTick), kTick).position;
  EXPECT_GE(end.x, 0.05);
}

TEST(FlockingStepTest, ReportsFleeingAndNeighbourCount) {
  Perception in = At(5.0, 5.6, 0.0);
  in.others = {Robot(2, 5.5, 5.6), Robot(3, 4.5, 5.6), Robot(4, 8.0, 8.0)};
  in.zones = {Zone{1, Shape::FromRect({5.0, 5.0}, {2.0, 2.0}), false}};
  Rng rng(1, 0);
  const MoveDecision d = FlockingStep(in, Quiet(), rng, kTick);
  EXPECT_TRUE(d.fleeing);
  EXPECT_EQ(d.neighbours_in_range, 3);
  EXPECT_EQ(d.desired_heading, Angle(90));
}

TEST(FlockingStepTest, SameSeedGivesTheSameDecision) {
  FlockingParams p = Quiet();
  p.free_will_deg = 120.0;
  p.cohesion = 0.3;
  Perception in = At(5.0, 5.0, 10.0);
  in.others = {Robot(2, 5.3, 5.1, 80.0), Robot(3, 4.9, 4.6, 200.0), Robot(4, 5.12, 5.0)};
  Rng first(99, 4);
  Rng second(99, 4);
  for (int i = 0; i < 20; ++i) {
    const MoveDecision a = FlockingStep(in, p, first, kTick);
    const MoveDecision b = FlockingStep(in, p, second, kTick);
    EXPECT_EQ(a.heading.degrees(), b.heading.degrees());
    EXPECT_EQ(a.distance_m, b.distance_m);
    EXPECT_EQ(a.outcome, b.outcome);
  }
}

// The simulator pushes overlapping robots apart to exactly 2r; rounded to float32 they sit a
// hair beyond touching. Facing each other, every arc starts towards the other robot, so a path
// check against it would refuse every move and leave both stuck for good.
TEST(AvoidCollisionsTest, RobotPushedToTouchingCanMoveAway) {
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 5.10000005, 5.0, 180.0)};
  const MoveDecision d = AvoidCollisions(in, Quiet(), Angle(0.0), kTick);
  EXPECT_NE(d.outcome, MoveOutcome::kStand);
  EXPECT_GT(d.distance_m, 0.0);
  const Vec2 to =
      TurnThenDrive(in.self, CommandFor(in.self, d.heading, d.distance_m, kTick), kTick).position;
  EXPECT_GT(Distance(to, {5.10000005, 5.0}), 0.10000005);
}

// A robot touching three others spaced 120 degrees apart (left as the simulator's push leaves
// them): every direction brings it closer to one of them, yet the jam must dissolve, so a move
// that lowers the summed overlap is valid.
TEST(AvoidCollisionsTest, JammedRobotCanStillMove) {
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 4.9, 5.0), Robot(3, 5.05, 5.0 + 0.05 * std::sqrt(3.0)),
               Robot(4, 5.05, 5.0 - 0.05 * std::sqrt(3.0))};
  const MoveDecision d = AvoidCollisions(in, Quiet(), Angle(0.0), kTick);
  EXPECT_NE(d.outcome, MoveOutcome::kStand);
  const Vec2 to =
      TurnThenDrive(in.self, CommandFor(in.self, d.heading, d.distance_m, kTick), kTick).position;
  double after = 0.0;
  for (const Neighbour& n : in.others) after += std::max(0.0, 0.11 - Distance(to, n.position));
  EXPECT_LT(after, 3 * (0.11 - 0.10));
}

// ... but a move that comes too close to a robot that was at a safe distance stays invalid.
TEST(AvoidCollisionsTest, EscapingAJamMayNotCloseInOnAThirdRobot) {
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 4.9, 5.0), Robot(3, 5.2, 5.0)};
  // Straight ahead moves 0.1 m away from robot 2 but ends 0.1 m from robot 3.
  EXPECT_FALSE(IsMoveValid(in, Quiet(), Angle(0.0), 0.1, kTick));
  EXPECT_TRUE(IsMoveValid(in, Quiet(), Angle(90.0), 0.1, kTick));
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
