#include "swarm_transport/core/leader.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr double kTolerance = 1e-9;
constexpr double kTick = 1.0;

// Flocking parameters a leader must ignore (free will, cohesion) are deliberately non-zero.
FlockingParams Params() {
  FlockingParams p;
  p.local_range_m = 1.0;
  p.speed_m_per_tick = 0.1;
  p.free_will_deg = 90.0;
  p.cohesion = 0.5;
  p.speed_reduction = 0.5;
  p.speed_retries = 2;
  return p;
}

LeaderParams Alone() {
  LeaderParams lp;
  lp.keep_flock = false;
  return lp;
}

Neighbour Robot(std::uint16_t id, double x, double y, std::uint8_t type = 0) {
  Neighbour n;
  n.id = id;
  n.type = type;
  n.position = {x, y};
  n.heading = Angle(180);
  return n;
}

// The perceiving robot.
constexpr auto At = fixtures::PerceptionAt;

TEST(LeaderParamsTest, ValidatesToleranceAndWaitFraction) {
  EXPECT_EQ(LeaderParams().Validate(), "");
  LeaderParams tolerance;
  tolerance.goal_tolerance_m = 0.0;
  EXPECT_EQ(tolerance.Validate(), "goal_tolerance_m must be finite and > 0 but is 0");
  LeaderParams fraction;
  fraction.wait_fraction = 1.5;
  EXPECT_EQ(fraction.Validate(), "wait_fraction must be in (0, 1] but is 1.5");
  fraction.wait_fraction = 1.0;
  EXPECT_EQ(fraction.Validate(), "");
}

TEST(LeaderStepTest, HeadsForTheGoalIgnoringTheFlock) {
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 5.3, 5.0)};  // heading 180 and east of it: alignment, cohesion would turn
  Rng rng(1, 0);
  LeaderMemory memory;
  const LeaderDecision d =
      LeaderStep(in, Params(), Alone(), {5.0, 8.0}, Angle(90), rng, kTick, &memory);
  EXPECT_FALSE(d.arrived);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStraight);
  EXPECT_EQ(d.move.heading, Angle(90));
  EXPECT_NEAR(d.move.distance_m, 0.1, kTolerance);
}

TEST(LeaderStepTest, StopsAtTheGoalInsteadOfOvershooting) {
  Rng rng(1, 0);
  LeaderMemory memory;
  const LeaderDecision d = LeaderStep(At(5.0, 5.0, 90.0), Params(), Alone(), {5.0, 5.08}, Angle(90),
                                      rng, kTick, &memory);
  EXPECT_NEAR(d.move.distance_m, 0.08, kTolerance);
}

TEST(LeaderStepTest, NeverSwervesWhenBlocked) {
  // A thin danger strip covers the straight line ahead at every speed; one degree aside is free
  // (a normal robot swerves there), but a leader stands.
  Perception in = At(5.0, 5.0, 90.0);
  in.zones = {Zone{1, Shape::FromRect({5.0, 5.06}, {0.0012, 0.1}), false}};
  ASSERT_EQ(AvoidCollisions(in, Params(), Angle(90), kTick).outcome, MoveOutcome::kSwerved);
  Rng rng(1, 0);
  LeaderMemory memory;
  const LeaderDecision d =
      LeaderStep(in, Params(), Alone(), {5.0, 8.0}, Angle(90), rng, kTick, &memory);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStand);
  EXPECT_EQ(d.move.distance_m, 0.0);
  EXPECT_EQ(d.move.heading, Angle(90));
  EXPECT_EQ(memory.blocked_waits, 1u);
}

TEST(LeaderStepTest, WithoutItsCollisionTestDrivesThroughRobotsButNotZonesOrTheBorder) {
  // A robot straight ahead, 0.06 m away: every speed on the course collides.
  Perception in = At(5.0, 5.0, 90.0);
  in.others = {Robot(2, 5.0, 5.06)};
  LeaderParams checked = Alone();
  LeaderParams through = Alone();
  through.check_collisions = false;
  Rng rng(1, 0);
  LeaderMemory memory;
  LeaderDecision d = LeaderStep(in, Params(), checked, {5.0, 8.0}, Angle(90), rng, kTick, &memory);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStand);
  EXPECT_EQ(memory.blocked_waits, 1u);
  LeaderMemory free_memory;
  d = LeaderStep(in, Params(), through, {5.0, 8.0}, Angle(90), rng, kTick, &free_memory);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStraight);
  EXPECT_NEAR(d.move.distance_m, 0.1, kTolerance);
  EXPECT_EQ(d.move.heading, Angle(90));
  EXPECT_EQ(free_memory.blocked_waits, 0u);
  // A danger strip ahead still stops it.
  in.zones = {Zone{1, Shape::FromRect({5.0, 5.06}, {0.0012, 0.1}), false}};
  LeaderMemory zone_memory;
  d = LeaderStep(in, Params(), through, {5.0, 8.0}, Angle(90), rng, kTick, &zone_memory);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStand);
  EXPECT_EQ(zone_memory.blocked_waits, 1u);
  // So does the arena border.
  Perception edge = At(5.0, Params().world_size_m - Params().robot_radius_m, 90.0);
  LeaderMemory edge_memory;
  d = LeaderStep(edge, Params(), through, {5.0, 20.0}, Angle(90), rng, kTick, &edge_memory);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStand);
}

TEST(LeaderStepTest, TwoLeadersHeadOnStandForGoodUnlessTheySwerveAfterBlockedTicks) {
  // Two leaders touching, each heading for the other's side (as the flood test found): every
  // speed on either course comes closer to the other.
  Perception a = At(5.0, 5.0, 0.0);
  a.others = {Robot(2, 5.1, 5.0)};
  Perception b = At(5.1, 5.0, 180.0);
  b.self_id = 2;
  b.others = {Robot(1, 5.0, 5.0)};
  for (const int after : {0, 3}) {
    LeaderParams lp = Alone();
    lp.swerve_after_blocked_ticks = after;
    Rng rng(1, 0);
    LeaderMemory ma;
    LeaderMemory mb;
    for (int tick = 1; tick <= 10; ++tick) {
      const LeaderDecision da = LeaderStep(a, Params(), lp, {8.0, 5.0}, Angle(0), rng, kTick, &ma);
      const LeaderDecision db =
          LeaderStep(b, Params(), lp, {2.0, 5.0}, Angle(180), rng, kTick, &mb);
      const bool swerving = after > 0 && tick > after;
      EXPECT_EQ(da.move.outcome == MoveOutcome::kStand, !swerving) << after << " " << tick;
      EXPECT_EQ(db.move.outcome == MoveOutcome::kStand, !swerving) << after << " " << tick;
      if (swerving) {
        // Off its course, and not into the other.
        EXPECT_GT(da.move.distance_m, 0.0);
        EXPECT_GT(db.move.distance_m, 0.0);
        EXPECT_NE(da.move.heading, Angle(0));
        EXPECT_NE(db.move.heading, Angle(180));
        EXPECT_TRUE(IsMoveValid(a, Params(), da.move.heading, da.move.distance_m, kTick));
      }
    }
    EXPECT_EQ(ma.blocked_waits, 10u);
    EXPECT_EQ(ma.blocked_in_a_row, 10u);
  }
  LeaderParams bad;
  bad.swerve_after_blocked_ticks = -1;
  EXPECT_NE(bad.Validate(), "");
}

TEST(LeaderStepTest, SlowsDownWhenOnlyFullSpeedIsBlocked) {
  Perception in = At(5.0, 5.0, 90.0);
  in.zones = {Zone{1, Shape::FromRect({5.0, 5.1}, {0.01, 0.04}), false}};
  Rng rng(1, 0);
  LeaderMemory memory;
  const LeaderDecision d =
      LeaderStep(in, Params(), Alone(), {5.0, 8.0}, Angle(90), rng, kTick, &memory);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kSlowed);
  EXPECT_EQ(d.move.heading, Angle(90));
  EXPECT_NEAR(d.move.distance_m, 0.05, kTolerance);
  EXPECT_EQ(memory.blocked_waits, 0u);
}

TEST(LeaderStepTest, WaitsWhileTheSwarmCentroidIsBeyondHalfTheRange) {
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 4.4, 5.0), Robot(3, 4.2, 5.0)};  // centroid 0.7 behind
  Rng rng(1, 0);
  LeaderMemory memory;
  const LeaderDecision d =
      LeaderStep(in, Params(), LeaderParams(), {8.0, 5.0}, Angle(0), rng, kTick, &memory);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStand);
  EXPECT_EQ(d.move.distance_m, 0.0);
  EXPECT_EQ(memory.swarm_waits, 1u);
  EXPECT_FALSE(memory.gave_up);
}

TEST(LeaderStepTest, WithCentroidWithSelfTheLeaderCountsInTheCentroidItWaitsFor) {
  // Two robots 0.7 behind: their centroid is beyond half the range (0.5), but with the leader
  // counted once beside them (the evaluated code's findFlock) it is 0.7 * 2 / 3 = 0.47 away.
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 4.3, 5.0), Robot(3, 4.3, 5.0)};
  LeaderParams with_self;
  with_self.centroid_with_self = true;
  Rng rng(1, 0);
  LeaderMemory memory;
  LeaderDecision d = LeaderStep(in, Params(), with_self, {8.0, 5.0}, Angle(0), rng, kTick, &memory);
  EXPECT_EQ(memory.swarm_waits, 0u);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStraight);
  LeaderMemory plain;
  d = LeaderStep(in, Params(), LeaderParams(), {8.0, 5.0}, Angle(0), rng, kTick, &plain);
  EXPECT_EQ(plain.swarm_waits, 1u);
  // 0.8 behind: 0.53 with the leader counted, so it waits as well.
  in.others = {Robot(2, 4.2, 5.0), Robot(3, 4.2, 5.0)};
  d = LeaderStep(in, Params(), with_self, {8.0, 5.0}, Angle(0), rng, kTick, &memory);
  EXPECT_EQ(memory.swarm_waits, 1u);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStand);
}

TEST(LeaderStepTest, WithGiveUpBeyondRangeALeaderLeavesASwarmWhoseCentreLeftItsRange) {
  // A chain behind the leader: one robot 0.4 behind (in range 1.0), four 1.4 behind (out of
  // its range, in the chain through the first): their centroid is 1.2 behind.
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 4.6, 5.0), Robot(3, 3.6, 5.0), Robot(4, 3.6, 5.1), Robot(5, 3.6, 4.9),
               Robot(6, 3.6, 5.2)};
  Rng rng(1, 0);
  // The default (the evaluated code: no give-up while a robot of its swarm is in range): it
  // waits for the far centroid, tick after tick.
  LeaderMemory waits;
  LeaderDecision d =
      LeaderStep(in, Params(), LeaderParams(), {8.0, 5.0}, Angle(0), rng, kTick, &waits);
  d = LeaderStep(in, Params(), LeaderParams(), {8.0, 5.0}, Angle(0), rng, kTick, &waits);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStand);
  EXPECT_EQ(waits.swarm_waits, 2u);
  EXPECT_FALSE(waits.gave_up);
  // The thesis text's rule: the centre left the range, it goes on alone and never waits again.
  LeaderParams text;
  text.give_up_beyond_range = true;
  LeaderMemory gone;
  d = LeaderStep(in, Params(), text, {8.0, 5.0}, Angle(0), rng, kTick, &gone);
  EXPECT_TRUE(gone.gave_up);
  EXPECT_EQ(gone.swarm_waits, 0u);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStraight);
  EXPECT_NEAR(d.move.distance_m, 0.1, kTolerance);
  // Even once the swarm is close and behind again.
  in.others = {Robot(2, 4.3, 5.0)};
  d = LeaderStep(in, Params(), text, {8.0, 5.0}, Angle(0), rng, kTick, &gone);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStraight);
  EXPECT_EQ(gone.swarm_waits, 0u);
  // Within the range (0.7 behind: beyond half of it) the rule still waits.
  LeaderMemory near;
  d = LeaderStep(in, Params(), text, {8.0, 5.0}, Angle(0), rng, kTick, &near);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStand);
  EXPECT_EQ(near.swarm_waits, 1u);
  EXPECT_FALSE(near.gave_up);
}

TEST(LeaderStepTest, WithWaitBehindWaitsOnlyForASwarmBehindIt) {
  // The thesis's leader code meant to wait only while its swarm's centroid was more than 90 deg off
  // its course: a swarm ahead or beside it is led, not waited for.
  const LeaderParams behind;  // the default
  ASSERT_TRUE(behind.wait_behind);
  const Vec2 goal{8.0, 5.0};  // course 0 deg
  struct Case {
    double x, y;
    bool waits;
  };
  // Centroids 0.7 away (beyond half the range): ahead, beside (89 deg), behind (91 deg, 180).
  const Case cases[] = {{5.7, 5.0, false},
                        {5.0 + 0.7 * std::cos(89.0 * M_PI / 180.0), 5.7, false},
                        {5.0 + 0.7 * std::cos(91.0 * M_PI / 180.0), 5.7, true},
                        {4.3, 5.0, true}};
  for (const Case& c : cases) {
    Perception in = At(5.0, 5.0, 0.0);
    in.others = {Robot(2, c.x, c.y)};
    Rng rng(1, 0);
    LeaderMemory memory;
    const LeaderDecision d = LeaderStep(in, Params(), behind, goal, Angle(0), rng, kTick, &memory);
    EXPECT_EQ(memory.swarm_waits, c.waits ? 1u : 0u) << c.x << ", " << c.y;
    EXPECT_EQ(d.move.outcome, c.waits ? MoveOutcome::kStand : MoveOutcome::kStraight);
    // Without the option it waits for every one of them.
    LeaderParams anywhere;
    anywhere.wait_behind = false;
    LeaderMemory plain;
    LeaderStep(in, Params(), anywhere, goal, Angle(0), rng, kTick, &plain);
    EXPECT_EQ(plain.swarm_waits, 1u);
  }
}

TEST(LeaderStepTest, WithEvaluatedAnglesWaitsOnlyForASwarmBehindOnItsLeft) {
  // The evaluated leader code's arithmetic: on a course of 45 deg it waited only for a
  // centroid bearing in (135, 180] deg; one straight behind (225) or behind on the right (300)
  // did not hold it, although wait_behind would.
  LeaderParams evaluated;
  evaluated.wait_evaluated_angles = true;
  const Vec2 goal{8.0, 8.0};  // course 45 deg from (5, 5)
  struct Case {
    double bearing_deg;
    bool waits_evaluated, waits_behind;
  };
  const Case cases[] = {{100.0, false, false}, {140.0, true, true},  {170.0, true, true},
                        {190.0, false, true},  {225.0, false, true}, {300.0, false, true},
                        {45.0, false, false}};
  for (const Case& c : cases) {
    const double rad = c.bearing_deg * M_PI / 180.0;
    Perception in = At(5.0, 5.0, 45.0);
    in.others = {Robot(2, 5.0 + 0.7 * std::cos(rad), 5.0 + 0.7 * std::sin(rad))};
    for (const bool use_evaluated : {true, false}) {
      Rng rng(1, 0);
      LeaderMemory memory;
      const LeaderDecision d = LeaderStep(in, Params(), use_evaluated ? evaluated : LeaderParams(),
                                          goal, Angle(45), rng, kTick, &memory);
      const bool waits = use_evaluated ? c.waits_evaluated : c.waits_behind;
      EXPECT_EQ(memory.swarm_waits, waits ? 1u : 0u) << c.bearing_deg << " " << use_evaluated;
      EXPECT_EQ(d.move.outcome, waits ? MoveOutcome::kStand : MoveOutcome::kStraight);
    }
  }
  // A centroid within half the range never holds it, whatever its side.
  Perception near = At(5.0, 5.0, 45.0);
  near.others = {Robot(2, 4.7, 5.1)};
  Rng rng(1, 0);
  LeaderMemory memory;
  LeaderStep(near, Params(), evaluated, goal, Angle(45), rng, kTick, &memory);
  EXPECT_EQ(memory.swarm_waits, 0u);
}

TEST(LeaderStepTest, MovesWhileTheSwarmCentroidIsWithinHalfTheRange) {
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 4.7, 5.0), Robot(3, 4.5, 5.0),  // centroid 0.4 away
               Robot(9, 1.0, 1.0, 2)};                  // a statist is no swarm member
  Rng rng(1, 0);
  LeaderMemory memory;
  const LeaderDecision d =
      LeaderStep(in, Params(), LeaderParams(), {8.0, 5.0}, Angle(0), rng, kTick, &memory);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStraight);
  EXPECT_EQ(memory.swarm_waits, 0u);
}

TEST(LeaderStepTest, GivesUpWhenNoRobotIsInRange) {
  Perception in = At(5.0, 5.0, 0.0);
  in.others = {Robot(2, 7.0, 5.0)};
  Rng rng(1, 0);
  LeaderMemory memory;
  LeaderDecision d =
      LeaderStep(in, Params(), LeaderParams(), {8.0, 5.0}, Angle(0), rng, kTick, &memory);
  EXPECT_TRUE(memory.gave_up);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStraight);
  // Having given up, a far centroid behind it no longer makes it wait.
  in.others = {Robot(2, 4.2, 5.0)};
  d = LeaderStep(in, Params(), LeaderParams(), {8.0, 5.0}, Angle(0), rng, kTick, &memory);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStraight);
  EXPECT_EQ(memory.swarm_waits, 0u);
}

TEST(LeaderStepTest, ArrivesWithinTheGoalTolerance) {
  Rng rng(1, 0);
  LeaderMemory memory;
  const LeaderDecision d = LeaderStep(At(5.0, 5.0, 0.0), Params(), Alone(), {5.03, 5.03}, Angle(45),
                                      rng, kTick, &memory);
  EXPECT_TRUE(d.arrived);
  EXPECT_EQ(d.move.outcome, MoveOutcome::kStand);
  EXPECT_EQ(d.move.distance_m, 0.0);
  EXPECT_EQ(memory.blocked_waits, 0u);
}

TEST(LeaderStepTest, AdvancesTheRandomSequenceLikeAFlockingStep) {
  Rng rng(5, 1);
  Rng reference(5, 1);
  LeaderMemory memory;
  LeaderStep(At(5.0, 5.0, 0.0), Params(), Alone(), {8.0, 5.0}, Angle(0), rng, kTick, &memory);
  FlockingStep(At(5.0, 5.0, 0.0), Params(), reference, kTick);
  EXPECT_EQ(rng.Next(), reference.Next());
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
