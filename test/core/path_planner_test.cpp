// Paths around danger (SPEC 9.8): the straight line when it is clear, a path through a gap and
// out of a U-shaped zone, every leg clear of the zones, and no path where there is none.
#include "swarm_transport/core/path_planner.h"

#include <gtest/gtest.h>

#include <vector>

#include "fixtures.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr auto Rect = fixtures::RectZone;
constexpr auto Params = fixtures::WithClearance;

// Every leg of the path from `from` is clear and the path ends at `to`.
void ExpectClearPath(Vec2 from, Vec2 to, const std::vector<Vec2>& path,
                     const std::vector<Zone>& zones, const PathParams& p) {
  ASSERT_FALSE(path.empty());
  EXPECT_NEAR(Distance(path.back(), to), 0.0, 1e-9);
  Vec2 at = from;
  for (const Vec2& w : path) {
    EXPECT_TRUE(SegmentClear(at, w, zones, p))
        << "(" << at.x << ", " << at.y << ") -> (" << w.x << ", " << w.y << ")";
    at = w;
  }
}

constexpr auto Length = fixtures::PolylineLength;

TEST(PathPlannerTest, TheStraightLineWhenItIsClear) {
  const std::vector<Zone> zones = {Rect(-1, 8, 8, 9, 9)};
  const auto path = PlanPath({2, 2}, {5, 2}, zones, Params(0.5));
  ASSERT_TRUE(path);
  ASSERT_EQ(path->size(), 1u);
  EXPECT_NEAR(path->front().x, 5.0, 1e-12);
}

TEST(PathPlannerTest, ThroughTheGapOfAWall) {
  // A wall across the arena at x 5..6 with a gap at y 8..9.
  const std::vector<Zone> zones = {Rect(-1, 5, 0, 6, 8), Rect(-2, 5, 9, 6, 11.088889)};
  const PathParams p = Params(0.2);
  ASSERT_FALSE(SegmentClear({2, 3}, {9, 3}, zones, p));
  const auto path = PlanPath({2, 3}, {9, 3}, zones, p);
  ASSERT_TRUE(path);
  ExpectClearPath({2, 3}, {9, 3}, *path, zones, p);
  bool through_gap = false;
  for (const Vec2& w : *path) through_gap |= w.y > 7.9 && w.y < 9.1;
  EXPECT_TRUE(through_gap);
}

TEST(PathPlannerTest, OutOfAUShapedZoneAndAroundIt) {
  // A U open to the top; the object starts inside it, the target is below its bottom bar.
  const std::vector<Zone> zones = {Rect(-1, 3.5, 3.5, 7.5, 4.0), Rect(-2, 3.5, 3.5, 4.0, 7.5),
                                   Rect(-3, 7.0, 3.5, 7.5, 7.5)};
  const PathParams p = Params(0.3);
  const Vec2 from{5.5, 5.5};
  const Vec2 to{5.5, 2.0};
  const auto path = PlanPath(from, to, zones, p);
  ASSERT_TRUE(path);
  ExpectClearPath(from, to, *path, zones, p);
  // Up out of the U (above 7.5 + clearance), around a side and down: far longer than 3.5 m.
  double top = 0.0;
  for (const Vec2& w : *path) top = std::max(top, w.y);
  EXPECT_GT(top, 7.5);
  EXPECT_GT(Length(from, *path), 9.0);
  EXPECT_LT(Length(from, *path), 14.0);  // not a detour over the whole arena
}

TEST(PathPlannerTest, NoPathToABlockedOrEnclosedTarget) {
  const PathParams p = Params(0.2);
  EXPECT_FALSE(PlanPath({2, 2}, {8.5, 8.5}, {Rect(-1, 8, 8, 9, 9)}, p));
  // A closed box around the target.
  const std::vector<Zone> box = {Rect(-1, 7, 7, 10, 7.3), Rect(-2, 7, 9.7, 10, 10),
                                 Rect(-3, 7, 7, 7.3, 10), Rect(-4, 9.7, 7, 10, 10)};
  EXPECT_FALSE(PlanPath({2, 2}, {8.5, 8.5}, box, p));
  // Too wide for the gap: clearance 0.6 m on each side of a 1 m gap.
  const std::vector<Zone> wall = {Rect(-1, 5, 0, 6, 8), Rect(-2, 5, 9, 6, 11.088889)};
  EXPECT_FALSE(PlanPath({2, 3}, {9, 3}, wall, Params(0.6)));
  // Outside the arena.
  EXPECT_FALSE(PlanPath({2, 2}, {12, 2}, {}, p));
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
