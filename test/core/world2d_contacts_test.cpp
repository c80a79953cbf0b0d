// World2D::ResolveContacts against the rule it implements, searched over all pairs: up to five
// passes, each pushing apart every pair closer than the contact distance at the pass's start
// (in id order, a pair an earlier push separated left alone), then clamping into the arena.
// The world searches only around the robots the pass before moved and keeps its grids between
// passes; the poses must be those of the full search, bit for bit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <utility>
#include <vector>

#include "swarm_transport/core/random.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace sim {
namespace {

// The rule over all pairs: `points` in id order.
void PushApartEveryPair(const WorldParams& params, std::vector<core::Vec2>* points) {
  std::vector<core::Vec2>& p = *points;
  const double contact = 2.0 * params.robot_radius_m;
  const double lo = params.robot_radius_m;
  const double hi = params.world_size_m - params.robot_radius_m;
  for (int pass = 0; pass < 5; ++pass) {
    std::vector<std::pair<std::size_t, std::size_t>> pairs;
    for (std::size_t i = 0; i < p.size(); ++i) {
      for (std::size_t j = i + 1; j < p.size(); ++j) {
        if (core::SquaredDistance(p[i], p[j]) < contact * contact) pairs.emplace_back(i, j);
      }
    }
    bool pushed = false;
    for (const auto& pair : pairs) {
      core::Vec2& a = p[pair.first];
      core::Vec2& b = p[pair.second];
      const double dx = b.x - a.x;
      const double dy = b.y - a.y;
      const double d = std::sqrt(dx * dx + dy * dy);
      if (d >= contact) continue;
      double ux = 1.0;
      double uy = 0.0;
      if (d > 1e-12) {
        ux = dx / d;
        uy = dy / d;
      }
      const double half = 0.5 * (contact - d);
      a.x -= ux * half;
      a.y -= uy * half;
      b.x += ux * half;
      b.y += uy * half;
      pushed = true;
    }
    for (core::Vec2& q : p) q = {std::min(hi, std::max(lo, q.x)), std::min(hi, std::max(lo, q.y))};
    if (!pushed) break;
  }
}

bool SameBits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// Spawns `poses` (ids 0..), resolves the contacts and compares with the rule over all pairs.
void ExpectContactsAsEveryPair(const WorldParams& params, const std::vector<core::Vec2>& poses) {
  World2D world(params);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    ASSERT_TRUE(
        world.Spawn(static_cast<std::uint16_t>(i), core::Pose2{poses[i], core::Angle()}, nullptr));
  }
  std::vector<core::Vec2> expected;
  for (const auto& entry : world.robots()) expected.push_back(entry.second.pose.position);
  PushApartEveryPair(params, &expected);
  world.ResolveContacts();
  std::size_t i = 0;
  std::size_t moved = 0;
  for (const auto& entry : world.robots()) {
    const core::Vec2 got = entry.second.pose.position;
    EXPECT_TRUE(SameBits(got.x, expected[i].x) && SameBits(got.y, expected[i].y))
        << "robot " << entry.first << ": (" << got.x << ", " << got.y << ") instead of ("
        << expected[i].x << ", " << expected[i].y << ")";
    if (!SameBits(got.x, poses[i].x) || !SameBits(got.y, poses[i].y)) ++moved;
    ++i;
  }
  EXPECT_GT(moved, 0u);  // the case pushed someone
}

// A few robots crowded among many that stand apart: later passes search around the few (the
// robots moved since the first pass's grid in a grid of their own).
TEST(World2DContactsTest, AFewCrowdedAmongManyAsEveryPair) {
  WorldParams params;
  params.world_size_m = 40.0;
  core::Rng rng(11, 3);
  std::vector<core::Vec2> poses;
  for (int x = 0; x < 40; ++x) {
    for (int y = 0; y < 40; ++y) poses.push_back({0.5 + x, 0.5 + y});  // 1 m apart
  }
  for (int k = 0; k < 60; ++k) {
    poses.push_back({rng.Uniform(20.0, 20.4), rng.Uniform(20.0, 20.4)});  // a crowd
    poses.push_back({rng.Uniform(0.05, 0.3), rng.Uniform(39.7, 39.95)});  // one at a wall
  }
  ExpectContactsAsEveryPair(params, poses);
}

// Everyone overlaps someone: the moved robots soon outnumber an eighth of the swarm and the
// grid of everyone is built again.
TEST(World2DContactsTest, AWholeCrowdAsEveryPair) {
  for (const double side : {3.0, 150.0}) {  // a dense table of cells, and hashed cells
    WorldParams params;
    params.world_size_m = side;
    core::Rng rng(12, 4);
    std::vector<core::Vec2> poses;
    for (int k = 0; k < 700; ++k) poses.push_back({rng.Uniform(0.05, 2.0), rng.Uniform(0.05, 2.0)});
    poses.push_back(poses[5]);  // coincident
    ExpectContactsAsEveryPair(params, poses);
  }
}

}  // namespace
}  // namespace sim
}  // namespace swarm_transport
