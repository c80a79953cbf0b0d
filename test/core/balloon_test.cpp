#include "swarm_transport/core/balloon.h"

#include <gtest/gtest.h>

#include <algorithm>
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

// Nearest-neighbour spacing CV of `at` (population standard deviation / mean).
double SpacingCv(const std::vector<Vec2>& at) {
  std::vector<double> nearest;
  for (std::size_t i = 0; i < at.size(); ++i) {
    double n = 1e9;
    for (std::size_t j = 0; j < at.size(); ++j) {
      if (j != i) n = std::min(n, Distance(at[i], at[j]));
    }
    nearest.push_back(n);
  }
  double mean = 0.0;
  for (const double v : nearest) mean += v / static_cast<double>(nearest.size());
  double squares = 0.0;
  for (const double v : nearest) squares += (v - mean) * (v - mean);
  return std::sqrt(squares / static_cast<double>(nearest.size())) / mean;
}

// `ticks` ticks of LoadingBalloonStep (or, with `spread` false, of standing) for robots 0..n-1
// under a 2 x 2 object at (7, 7), robot 0 a leader facing 225 degrees; every robot hears every
// other (mission peers) and also robot 99, a bystander outside the object.
std::vector<Vec2> SpreadUnder(std::vector<Vec2> at, int ticks, bool spread, bool* left) {
  const FlockingParams p = fixtures::Quiet();
  BalloonParams bp;
  const Rect object{{7.0, 7.0}, {2.0, 2.0}};
  const Shape shape = Shape::FromRect(object.centre, object.size);
  std::vector<double> radius(at.size(), p.robot_radius_m);
  std::vector<std::uint16_t> ids;
  for (std::uint16_t i = 0; i < at.size(); ++i) ids.push_back(i);
  Rng rng(1, 1);
  *left = false;
  for (int tick = 0; tick < ticks && spread; ++tick) {
    std::vector<Vec2> next = at;
    for (std::uint16_t i = 0; i < at.size(); ++i) {
      std::vector<Neighbour> others{At(99, 8.3, 7.0)};
      std::vector<std::uint16_t> peers;
      for (std::uint16_t j = 0; j < at.size(); ++j) {
        if (j == i) continue;
        others.push_back(At(j, at[j].x, at[j].y));
        peers.push_back(j);
      }
      const MoveDecision d = LoadingBalloonStep(Self(i, at[i], others), p, bp, object, peers,
                                                i == 0, Angle(225.0), rng, kTick, &radius[i]);
      next[i] = at[i] + UnitVector(d.heading) * d.distance_m;
      if (!shape.Contains(next[i])) *left = true;
    }
    at = next;
  }
  return at;
}

TEST(BalloonTest, ParsesTheLoadingSpread) {
  LoadingSpread spread = LoadingSpread::kNone;
  EXPECT_TRUE(ParseLoadingSpread("balloon", &spread));
  EXPECT_EQ(spread, LoadingSpread::kBalloon);
  EXPECT_STREQ(LoadingSpreadName(spread), "balloon");
  EXPECT_TRUE(ParseLoadingSpread("none", &spread));
  EXPECT_EQ(spread, LoadingSpread::kNone);
  EXPECT_STREQ(LoadingSpreadName(spread), "none");
  EXPECT_FALSE(ParseLoadingSpread("flock", &spread));
  EXPECT_FALSE(ParseLoadingSpread("", &spread));
  EXPECT_EQ(spread, LoadingSpread::kNone);
}

TEST(BalloonTest, ObjectBordersReplaceTheArenasAndZonesAreLeftOut) {
  const FlockingParams p = Small();
  Perception in = Self(1, {6.5, 7.0}, {});
  Zone danger;
  danger.shape = Shape::FromRect({6.5, 7.6}, {0.2, 0.2});
  in.zones.push_back(danger);
  const std::vector<BalloonContact> c = BalloonContacts(in, p, Rect{{7.0, 7.0}, {2.0, 2.0}}, false);
  ASSERT_EQ(c.size(), 4u);                 // the object's four sides, no zone
  EXPECT_DOUBLE_EQ(c[0].distance_m, 0.5);  // left side at x = 6
  EXPECT_DOUBLE_EQ(c[1].distance_m, 1.0);  // bottom and top
  EXPECT_DOUBLE_EQ(c[2].distance_m, 1.0);
  EXPECT_DOUBLE_EQ(c[3].distance_m, 1.5);  // right
  EXPECT_EQ(BalloonContacts(in, p, Rect{{7.0, 7.0}, {2.0, 2.0}}, true).size(), 5u);
}

TEST(BalloonTest, RobotsBunchedInACornerOfTheirObjectSpreadUnderIt) {
  // Eight robots 0.15 m apart bunched in the object's lower-left corner and one in the opposite
  // corner: very uneven spacing (nearest neighbours 0.15 m and ~2 m).
  std::vector<Vec2> at;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i + j < 4) at.push_back({6.1 + 0.15 * i, 6.1 + 0.15 * j});
    }
  }
  at.push_back({7.9, 7.9});
  ASSERT_EQ(at.size(), 9u);
  const double before = SpacingCv(at);
  bool left = false;
  const std::vector<Vec2> stood = SpreadUnder(at, 200, false, &left);
  ASSERT_EQ(stood.size(), at.size());  // none: nothing moves
  for (std::size_t i = 0; i < at.size(); ++i) EXPECT_EQ(Distance(stood[i], at[i]), 0.0);
  const std::vector<Vec2> spread = SpreadUnder(at, 200, true, &left);
  EXPECT_FALSE(left) << "a robot left the object";
  const double after = SpacingCv(spread);
  EXPECT_LT(after, before / 2.0) << "before " << before << ", after " << after;
  double nearest = 1e9;
  for (std::size_t i = 0; i < spread.size(); ++i) {
    for (std::size_t j = i + 1; j < spread.size(); ++j) {
      nearest = std::min(nearest, Distance(spread[i], spread[j]));
    }
  }
  EXPECT_GT(nearest, 0.4);  // from 0.15 m to well apart under the 2 x 2 object
  for (const Vec2& a : spread) {
    EXPECT_GE(a.x, 6.0);
    EXPECT_LE(a.x, 8.0);
    EXPECT_GE(a.y, 6.0);
    EXPECT_LE(a.y, 8.0);
  }
}

TEST(BalloonTest, LoadingStepDrawsOneSampleAndALeaderStandingFacesItsCourse) {
  const FlockingParams p = fixtures::Quiet();
  BalloonParams bp;
  Rng a(3, 1);
  Rng b(3, 1);
  double r = p.robot_radius_m;
  // Alone in the middle of its object: its balloon grows, touches nothing yet: it stands.
  const MoveDecision d =
      LoadingBalloonStep(Self(0, {7.0, 7.0}, {}), p, bp, Rect{{7.0, 7.0}, {2.0, 2.0}}, {}, true,
                         Angle(225.0), a, kTick, &r);
  b.Uniform(0.0, 1.0);
  EXPECT_EQ(a.Next(), b.Next());
  EXPECT_EQ(d.distance_m, 0.0);
  EXPECT_NEAR(d.heading.degrees(), 225.0, 1e-9);
  EXPECT_NEAR(r, p.robot_radius_m + bp.growth_m_per_tick, 1e-12);
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
