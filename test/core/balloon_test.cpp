#include "swarm_transport/core/balloon.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fixtures.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr double kTick = 1.0;

using fixtures::At;

// Quiet flocking in a 3 x 3 m arena with a 2 m range: balloons grow up to 1 m.
FlockingParams Small() {
  FlockingParams p = fixtures::Quiet();
  p.world_size_m = 3.0;
  p.local_range_m = 2.0;
  return p;
}

Perception Self(std::uint16_t id, Vec2 at, std::vector<Neighbour> others) {
  Perception in;
  in.self_id = id;
  in.self = {at, Angle(0.0)};
  in.others = std::move(others);
  return in;
}

TEST(BalloonTest, ParsesItsModeAndRejectsABadGrowth) {
  StandbyMode mode = StandbyMode::kFlock;
  EXPECT_TRUE(ParseStandbyMode("balloon", &mode));
  EXPECT_EQ(mode, StandbyMode::kBalloon);
  EXPECT_STREQ(StandbyModeName(mode), "balloon");
  EXPECT_TRUE(ParseStandbyMode("flock", &mode));
  EXPECT_EQ(mode, StandbyMode::kFlock);
  EXPECT_FALSE(ParseStandbyMode("balloons", &mode));
  EXPECT_EQ(mode, StandbyMode::kFlock);
  BalloonParams bp;
  EXPECT_EQ(bp.Validate(), "");
  for (const double bad : {0.0, -0.1, std::nan("")}) {
    bp.growth_m_per_tick = bad;
    EXPECT_NE(bp.Validate().find("balloon_growth_m_per_tick"), std::string::npos) << bad;
  }
}

TEST(BalloonTest, ContactsAreHalfwayToRobotsInRangeAndTheBorders) {
  const FlockingParams p = Small();
  // A robot 1 m to the right touches at 0.5 m; one 3.1 m away is out of range.
  const Perception in = Self(1, {0.5, 1.0}, {At(2, 1.5, 1.0), At(3, 2.95, 2.95)});
  const std::vector<BalloonContact> c = BalloonContacts(in, p);
  ASSERT_EQ(c.size(), 5u);                 // one robot, four borders
  EXPECT_DOUBLE_EQ(c[0].distance_m, 0.5);  // the left border and the robot: 0.5 each
  EXPECT_DOUBLE_EQ(c[1].distance_m, 0.5);
  EXPECT_DOUBLE_EQ(c[2].distance_m, 1.0);  // bottom
  EXPECT_DOUBLE_EQ(c[3].distance_m, 2.0);  // top
  EXPECT_DOUBLE_EQ(c[4].distance_m, 2.5);  // right
}

TEST(BalloonTest, ARobotInACornerTouchingTwoBordersAndANeighbourStopsGrowing) {
  const FlockingParams p = Small();
  BalloonParams bp;
  bp.growth_m_per_tick = 0.02;
  // Corner robot at (0.5, 0.5): the borders 0.5 m left and below, a neighbour 1 m away on the
  // diagonal (its balloon meets this one at 0.5 m). The three contacts enclose it.
  const double s = 1.0 / std::sqrt(2.0);
  const Perception in = Self(1, {0.5, 0.5}, {At(2, 0.5 + s, 0.5 + s)});
  const std::vector<BalloonContact> contacts = BalloonContacts(in, p);
  double r = p.robot_radius_m;
  for (int tick = 0; tick < 100; ++tick) r = GrowBalloon(r, contacts, p, bp);
  // It grew in steps of 0.02 from 0.05 until it reached 0.5 (at 0.51), then stopped.
  EXPECT_NEAR(r, 0.51, 1e-9);
  EXPECT_TRUE(BalloonEnclosed(contacts, r));
  EXPECT_FALSE(BalloonEnclosed(contacts, 0.49));
  // Without the neighbour, nothing encloses it: it grows to half the local range.
  const std::vector<BalloonContact> alone = BalloonContacts(Self(1, {0.5, 0.5}, {}), p);
  r = p.robot_radius_m;
  for (int tick = 0; tick < 100; ++tick) r = GrowBalloon(r, alone, p, bp);
  EXPECT_DOUBLE_EQ(r, 1.0);
}

TEST(BalloonTest, TwoBordersAndANeighbourInALineLeaveAFreeSide) {
  // Left and bottom border and a neighbour straight to the right: up is free.
  const FlockingParams p = Small();
  const std::vector<BalloonContact> c = BalloonContacts(Self(1, {0.5, 0.5}, {At(2, 1.5, 0.5)}), p);
  EXPECT_FALSE(BalloonEnclosed(c, 0.51));
  // Its push points away from what it touches: the left border and the neighbour cancel, the
  // bottom border pushes it up.
  const Vec2 push = BalloonPush(c, 0.6);
  EXPECT_NEAR(push.x, 0.0, 1e-12);
  EXPECT_NEAR(push.y, 0.1, 1e-12);
}

TEST(BalloonTest, ThreeRobotsInALineSpreadEvenly) {
  // Three robots bunched in the middle of a 3 x 3 m arena at y = 1.5, all ticking together:
  // at the balance each balloon overlaps its two sides equally: x = 0.5, 1.5, 2.5.
  const FlockingParams p = Small();
  BalloonParams bp;
  std::vector<Vec2> at{{1.3, 1.5}, {1.5, 1.5}, {1.7, 1.5}};
  std::vector<double> radius(3, p.robot_radius_m);
  Rng rng(1, 1);
  for (int tick = 0; tick < 300; ++tick) {
    std::vector<Vec2> next = at;
    for (std::uint16_t i = 0; i < 3; ++i) {
      std::vector<Neighbour> others;
      for (std::uint16_t j = 0; j < 3; ++j) {
        if (j != i) others.push_back(At(j, at[j].x, at[j].y));
      }
      const MoveDecision d = BalloonStep(Self(i, at[i], others), p, bp, rng, kTick, &radius[i]);
      next[i] = at[i] + UnitVector(d.heading) * d.distance_m;
    }
    at = next;
  }
  EXPECT_NEAR(at[0].x, 0.5, 0.02);
  EXPECT_NEAR(at[1].x, 1.5, 0.02);
  EXPECT_NEAR(at[2].x, 2.5, 0.02);
  for (const Vec2& a : at) EXPECT_NEAR(a.y, 1.5, 1e-6);
}

TEST(BalloonTest, AClusterSpreadsAndKeepsItsDistances) {
  // Nine robots in a 3 x 3 block 0.2 m apart in an 11 x 11 arena, range 2: after 400 ticks the
  // nearest neighbours are far apart and no robot came closer than the separation.
  FlockingParams p = fixtures::Quiet();
  p.world_size_m = 11.0;
  p.local_range_m = 2.0;
  BalloonParams bp;
  std::vector<Vec2> at;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) at.push_back({5.3 + 0.2 * i, 5.3 + 0.2 * j});
  }
  std::vector<double> radius(at.size(), p.robot_radius_m);
  Rng rng(1, 1);
  double closest = 1e9;
  for (int tick = 0; tick < 400; ++tick) {
    std::vector<Vec2> next = at;
    for (std::uint16_t i = 0; i < at.size(); ++i) {
      std::vector<Neighbour> others;
      for (std::uint16_t j = 0; j < at.size(); ++j) {
        if (j != i) others.push_back(At(j, at[j].x, at[j].y));
      }
      const MoveDecision d = BalloonStep(Self(i, at[i], others), p, bp, rng, kTick, &radius[i]);
      next[i] = at[i] + UnitVector(d.heading) * d.distance_m;
    }
    at = next;
    for (std::size_t i = 0; i < at.size(); ++i) {
      for (std::size_t j = i + 1; j < at.size(); ++j) {
        closest = std::min(closest, Distance(at[i], at[j]));
      }
    }
  }
  // Simultaneous moves are each checked against the others' old places: allow one step.
  EXPECT_GT(closest, p.MinSeparation() - p.speed_m_per_tick);
  for (std::size_t i = 0; i < at.size(); ++i) {
    double nearest = 1e9;
    for (std::size_t j = 0; j < at.size(); ++j) {
      if (j != i) nearest = std::min(nearest, Distance(at[i], at[j]));
    }
    EXPECT_GT(nearest, 1.5) << "robot " << i;
  }
}

TEST(BalloonTest, StepDrawsOneSampleAndFleesFromAForbiddenPlace) {
  const FlockingParams p = Small();
  BalloonParams bp;
  Rng a(3, 1);
  Rng b(3, 1);
  double r = p.robot_radius_m;
  BalloonStep(Self(1, {1.5, 1.5}, {}), p, bp, a, kTick, &r);
  b.Uniform(0.0, 1.0);
  EXPECT_EQ(a.Next(), b.Next());
  // Inside a danger zone it flees like a flocking robot (straight out, to the right here).
  Perception in = Self(1, {1.45, 1.5}, {});
  Zone danger;
  danger.shape = Shape::FromRect({1.0, 1.5}, {1.0, 1.0});
  in.zones.push_back(danger);
  const MoveDecision d = BalloonStep(in, p, bp, a, kTick, &r);
  EXPECT_TRUE(d.fleeing);
  EXPECT_NEAR(d.heading.degrees(), 0.0, 1e-6);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
