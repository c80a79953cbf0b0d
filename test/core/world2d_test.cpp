#include "swarm_transport/sim/world2d.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "swarm_transport/core/random.h"

namespace swarm_transport {
namespace sim {
namespace {

constexpr double kTol = 1e-9;
constexpr double kPi = 3.14159265358979323846;

core::Pose2 MakePose(double x, double y, double heading_deg) {
  return core::Pose2{{x, y}, core::Angle(heading_deg)};
}

double Dist(core::Vec2 a, core::Vec2 b) { return std::hypot(b.x - a.x, b.y - a.y); }

const Robot& Get(const World2D& world, std::uint16_t id) {
  const Robot* robot = world.Find(id);
  EXPECT_NE(robot, nullptr);
  return *robot;
}

TEST(WorldParamsTest, DefaultsAreValidAndBadValuesAreNamed) {
  EXPECT_EQ(WorldParams().Validate(), "");
  WorldParams p;
  p.world_size_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(p.Validate().find("world_size_m"), std::string::npos);
  p = WorldParams();
  p.robot_radius_m = 6.0;
  EXPECT_NE(p.Validate().find("robot_radius_m"), std::string::npos);
  p = WorldParams();
  p.integration_step_s = 0.0;
  EXPECT_NE(p.Validate().find("integration_step_s"), std::string::npos);
  p = WorldParams();
  p.command_duration_s = -1.0;
  EXPECT_NE(p.Validate().find("command_duration_s"), std::string::npos);
}

TEST(World2DTest, StraightDriveForCommandDurationThenStop) {
  World2D world{WorldParams()};  // command held 1 s
  ASSERT_TRUE(world.Spawn(0, MakePose(2.0, 3.0, 0.0), nullptr));
  ASSERT_TRUE(world.SetCommand(0, {0.5, 0.0}, nullptr));
  world.Step(0.5);
  EXPECT_NEAR(Get(world, 0).pose.position.x, 2.25, kTol);
  EXPECT_DOUBLE_EQ(Get(world, 0).last_velocity.linear, 0.5);
  world.Step(0.5);
  EXPECT_NEAR(Get(world, 0).pose.position.x, 2.5, kTol);
  world.Step(2.0);  // the command has expired: it stands
  EXPECT_NEAR(Get(world, 0).pose.position.x, 2.5, kTol);
  EXPECT_NEAR(Get(world, 0).pose.position.y, 3.0, kTol);
  EXPECT_DOUBLE_EQ(Get(world, 0).last_velocity.linear, 0.0);
  EXPECT_DOUBLE_EQ(Get(world, 0).command_remaining_s, 0.0);
}

TEST(World2DTest, CommandTurnsInPlaceThenDrivesStraight) {
  World2D world{WorldParams()};
  const core::Pose2 start = MakePose(5.0, 5.0, 30.0);
  ASSERT_TRUE(world.Spawn(7, start, nullptr));
  // angular pi/2 rad/s for the 1 s command: a 90 degree turn at once, then 1 m straight.
  const core::Velocity v{1.0, kPi / 2.0};
  ASSERT_TRUE(world.SetCommand(7, v, nullptr));
  world.Step(1.0);
  const core::Pose2 expected = core::TurnThenDrive(start, v, 1.0);
  EXPECT_NEAR(Get(world, 7).pose.position.x, expected.position.x, kTol);
  EXPECT_NEAR(Get(world, 7).pose.position.y, expected.position.y, kTol);
  EXPECT_NEAR(Get(world, 7).pose.heading.degrees(), 120.0, 1e-7);
  // Independent check of the geometry: 1 m along 120 degrees.
  const double t1 = 120.0 * kPi / 180.0;
  EXPECT_NEAR(Get(world, 7).pose.position.x, 5.0 + std::cos(t1), kTol);
  EXPECT_NEAR(Get(world, 7).pose.position.y, 5.0 + std::sin(t1), kTol);
}

TEST(World2DTest, CommandExpiresExactlyWithinAStep) {
  WorldParams params;
  params.command_duration_s = 0.25;
  World2D world(params);
  ASSERT_TRUE(world.Spawn(1, MakePose(1.0, 1.0, 90.0), nullptr));
  ASSERT_TRUE(world.SetCommand(1, {1.0, 0.0}, nullptr));
  world.Step(0.1);
  world.Step(0.1);
  world.Step(0.1);  // the command ends 0.05 s into this step
  EXPECT_NEAR(Get(world, 1).pose.position.x, 1.0, kTol);
  EXPECT_NEAR(Get(world, 1).pose.position.y, 1.25, kTol);
  EXPECT_DOUBLE_EQ(Get(world, 1).command_remaining_s, 0.0);
  // One step as long as the command in one go gives the same.
  World2D other(params);
  ASSERT_TRUE(other.Spawn(1, MakePose(1.0, 1.0, 90.0), nullptr));
  ASSERT_TRUE(other.SetCommand(1, {1.0, 0.0}, nullptr));
  other.Step(0.25);
  EXPECT_NEAR(Get(other, 1).pose.position.y, 1.25, kTol);
  EXPECT_DOUBLE_EQ(Get(other, 1).last_velocity.linear, 1.0);  // drove until the very end
}

TEST(World2DTest, CommandByIndexIsTheCommandById) {
  WorldParams params;
  World2D by_id(params);
  World2D by_index(params);
  for (World2D* world : {&by_id, &by_index}) {
    ASSERT_TRUE(world->Spawn(4, MakePose(2.0, 2.0, 10.0), nullptr));
    ASSERT_TRUE(world->Spawn(9, MakePose(6.0, 3.0, 200.0), nullptr));
  }
  ASSERT_TRUE(by_id.SetCommand(9, {0.7, -1.3}, nullptr));
  ASSERT_TRUE(by_index.SetCommandAt(1, {0.7, -1.3}, nullptr));  // robots() order: 4, 9
  std::string error;
  EXPECT_FALSE(by_index.SetCommandAt(2, {0.1, 0.0}, &error));
  EXPECT_NE(error.find("index 2"), std::string::npos);
  EXPECT_FALSE(by_index.SetCommandAt(0, {NAN, 0.0}, &error));
  EXPECT_EQ(error, "the velocity must be finite");
  by_id.Step(0.5);
  by_index.Step(0.5);
  for (std::uint16_t id : {4, 9}) {
    EXPECT_EQ(Get(by_id, id).pose.position.x, Get(by_index, id).pose.position.x);
    EXPECT_EQ(Get(by_id, id).pose.position.y, Get(by_index, id).pose.position.y);
    EXPECT_EQ(Get(by_id, id).pose.heading.degrees(), Get(by_index, id).pose.heading.degrees());
  }
  EXPECT_NE(Get(by_index, 9).pose.position.x, 6.0);
  EXPECT_EQ(Get(by_index, 4).pose.position.x, 2.0);  // the refused command changed nothing
}

TEST(World2DTest, NewCommandReplacesTheOldOneAndRestartsItsDuration) {
  WorldParams params;
  params.command_duration_s = 0.1;
  World2D world(params);
  ASSERT_TRUE(world.Spawn(0, MakePose(1.0, 1.0, 0.0), nullptr));
  ASSERT_TRUE(world.SetCommand(0, {1.0, 0.0}, nullptr));
  world.Step(0.05);
  ASSERT_TRUE(world.SetCommand(0, {2.0, 0.0}, nullptr));
  world.Step(1.0);
  EXPECT_NEAR(Get(world, 0).pose.position.x, 1.0 + 0.05 + 0.2, kTol);
}

TEST(World2DTest, ClampsAtTheBorder) {
  WorldParams params;
  World2D world(params);
  const double r = params.robot_radius_m;
  const double hi = params.world_size_m - r;
  ASSERT_TRUE(world.Spawn(0, MakePose(1.0, 1.0, 180.0), nullptr));
  ASSERT_TRUE(world.Spawn(1, MakePose(10.5, 10.5, 45.0), nullptr));
  ASSERT_TRUE(world.SetCommand(0, {5.0, 0.0}, nullptr));
  ASSERT_TRUE(world.SetCommand(1, {5.0, 0.0}, nullptr));
  world.Step(1.0);
  EXPECT_DOUBLE_EQ(Get(world, 0).pose.position.x, r);
  EXPECT_NEAR(Get(world, 0).pose.position.y, 1.0, kTol);
  EXPECT_DOUBLE_EQ(Get(world, 1).pose.position.x, hi);
  EXPECT_DOUBLE_EQ(Get(world, 1).pose.position.y, hi);
}

TEST(World2DTest, PushesTwoOverlappingRobotsApartSymmetrically) {
  WorldParams params;
  World2D world(params);
  const double r = params.robot_radius_m;
  ASSERT_TRUE(world.Spawn(3, MakePose(5.0, 5.0, 0.0), nullptr));
  ASSERT_TRUE(world.Spawn(4, MakePose(5.06, 5.03, 0.0), nullptr));
  world.Step(0.0);
  const core::Vec2 a = Get(world, 3).pose.position;
  const core::Vec2 b = Get(world, 4).pose.position;
  EXPECT_NEAR(Dist(a, b), 2.0 * r, kTol);
  // Symmetric: the midpoint stays, the direction stays.
  EXPECT_NEAR(0.5 * (a.x + b.x), 5.03, kTol);
  EXPECT_NEAR(0.5 * (a.y + b.y), 5.015, kTol);
  EXPECT_NEAR((b.y - a.y) / (b.x - a.x), 0.5, kTol);
}

TEST(World2DTest, CoincidentRobotsSeparateAlongXByIdOrder) {
  WorldParams params;
  World2D world(params);
  ASSERT_TRUE(world.Spawn(9, MakePose(4.0, 4.0, 0.0), nullptr));
  ASSERT_TRUE(world.Spawn(2, MakePose(4.0, 4.0, 0.0), nullptr));
  world.Step(0.0);
  EXPECT_NEAR(Get(world, 2).pose.position.x, 4.0 - params.robot_radius_m, kTol);
  EXPECT_NEAR(Get(world, 9).pose.position.x, 4.0 + params.robot_radius_m, kTol);
  EXPECT_DOUBLE_EQ(Get(world, 2).pose.position.y, 4.0);
}

TEST(World2DTest, PushApartCanBeSwitchedOff) {
  WorldParams params;
  params.push_apart = false;
  World2D world(params);
  ASSERT_TRUE(world.Spawn(0, MakePose(5.0, 5.0, 0.0), nullptr));
  ASSERT_TRUE(world.Spawn(1, MakePose(5.01, 5.0, 0.0), nullptr));
  world.Step(0.1);
  EXPECT_DOUBLE_EQ(Get(world, 1).pose.position.x, 5.01);
}

TEST(World2DTest, DeterministicRegardlessOfCommandOrder) {
  WorldParams params;
  params.command_duration_s = 0.1;
  const std::vector<core::Pose2> poses = PlaceCorner(100, params);  // a crowded start
  ASSERT_EQ(poses.size(), 100u);
  World2D a(params);
  World2D b(params);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    ASSERT_TRUE(a.Spawn(static_cast<std::uint16_t>(i), poses[i], nullptr));
    ASSERT_TRUE(b.Spawn(static_cast<std::uint16_t>(i), poses[i], nullptr));
  }
  core::Rng rng(42, 0);
  for (int tick = 0; tick < 50; ++tick) {
    std::vector<core::Velocity> commands;
    for (std::size_t i = 0; i < poses.size(); ++i) {
      commands.push_back({rng.Uniform(0.0, 2.0), rng.Uniform(-3.0, 3.0)});
    }
    for (std::size_t i = 0; i < poses.size(); ++i) {  // a: ascending, b: descending
      ASSERT_TRUE(a.SetCommand(static_cast<std::uint16_t>(i), commands[i], nullptr));
      const std::size_t j = poses.size() - 1 - i;
      ASSERT_TRUE(b.SetCommand(static_cast<std::uint16_t>(j), commands[j], nullptr));
    }
    a.Step(0.1);
    b.Step(0.1);
  }
  for (const auto& entry : a.robots()) {
    const Robot& other = Get(b, entry.first);
    EXPECT_EQ(entry.second.pose.position.x, other.pose.position.x);
    EXPECT_EQ(entry.second.pose.position.y, other.pose.position.y);
    EXPECT_EQ(entry.second.pose.heading.degrees(), other.pose.heading.degrees());
  }
}

TEST(World2DTest, SpawnRejectsDuplicateNonFiniteAndOutsideWithoutChangingState) {
  World2D world{WorldParams()};
  ASSERT_TRUE(world.Spawn(5, MakePose(1.0, 2.0, 10.0), nullptr));
  std::string error;
  EXPECT_FALSE(world.Spawn(5, MakePose(3.0, 3.0, 0.0), &error));
  EXPECT_NE(error.find("already exists"), std::string::npos);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(world.Spawn(6, MakePose(nan, 3.0, 0.0), &error));
  EXPECT_NE(error.find("finite"), std::string::npos);
  EXPECT_FALSE(world.Spawn(6, MakePose(3.0, 3.0, nan), &error));
  EXPECT_FALSE(world.Spawn(6, MakePose(-1.0, 3.0, 0.0), &error));
  EXPECT_NE(error.find("outside"), std::string::npos);
  EXPECT_FALSE(world.Spawn(6, MakePose(3.0, 11.08, 0.0), &error));
  EXPECT_EQ(world.size(), 1u);
  EXPECT_DOUBLE_EQ(Get(world, 5).pose.position.x, 1.0);
  EXPECT_DOUBLE_EQ(Get(world, 5).pose.position.y, 2.0);
  EXPECT_FALSE(world.SetCommand(5, {nan, 0.0}, &error));
  EXPECT_FALSE(world.SetCommand(6, {1.0, 0.0}, &error));
  EXPECT_NE(error.find("does not exist"), std::string::npos);
  EXPECT_DOUBLE_EQ(Get(world, 5).command_remaining_s, 0.0);
  EXPECT_TRUE(world.Kill(5, nullptr));
  EXPECT_FALSE(world.Kill(5, &error));
  EXPECT_EQ(world.size(), 0u);
}

TEST(World2DTest, Teleport) {
  World2D world{WorldParams()};
  ASSERT_TRUE(world.Spawn(0, MakePose(1.0, 1.0, 0.0), nullptr));
  ASSERT_TRUE(world.TeleportAbsolute(0, MakePose(4.0, 6.0, 270.0), nullptr));
  EXPECT_DOUBLE_EQ(Get(world, 0).pose.position.x, 4.0);
  EXPECT_DOUBLE_EQ(Get(world, 0).pose.position.y, 6.0);
  // Turn 90 degrees left (270 -> 0), then 1 m forward along +x.
  ASSERT_TRUE(world.TeleportRelative(0, 1.0, kPi / 2.0, nullptr));
  EXPECT_NEAR(Get(world, 0).pose.position.x, 5.0, kTol);
  EXPECT_NEAR(Get(world, 0).pose.position.y, 6.0, kTol);
  EXPECT_TRUE(Get(world, 0).pose.heading == core::Angle(0.0));
  // Relative moves stop at the wall; bad input changes nothing.
  ASSERT_TRUE(world.TeleportRelative(0, 100.0, 0.0, nullptr));
  EXPECT_DOUBLE_EQ(Get(world, 0).pose.position.x, 11.088889 - 0.05);
  std::string error;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(world.TeleportRelative(0, nan, 0.0, &error));
  EXPECT_FALSE(world.TeleportAbsolute(0, MakePose(20.0, 1.0, 0.0), &error));
  EXPECT_FALSE(world.TeleportAbsolute(1, MakePose(2.0, 1.0, 0.0), &error));
  EXPECT_DOUBLE_EQ(Get(world, 0).pose.position.x, 11.088889 - 0.05);
  EXPECT_DOUBLE_EQ(Get(world, 0).pose.position.y, 6.0);
}

TEST(World2DTest, ResetPutsRobotsBackAndClearsCommands) {
  World2D world{WorldParams()};
  ASSERT_TRUE(world.Spawn(0, MakePose(1.0, 1.0, 0.0), nullptr));
  ASSERT_TRUE(world.Spawn(1, MakePose(3.0, 3.0, 90.0), nullptr));
  ASSERT_TRUE(world.SetCommand(0, {1.0, 1.0}, nullptr));
  ASSERT_TRUE(world.TeleportAbsolute(1, MakePose(7.0, 7.0, 0.0), nullptr));
  world.Step(0.5);
  world.Reset();
  EXPECT_DOUBLE_EQ(Get(world, 0).pose.position.x, 1.0);
  EXPECT_DOUBLE_EQ(Get(world, 0).pose.heading.degrees(), 0.0);
  EXPECT_DOUBLE_EQ(Get(world, 1).pose.position.y, 3.0);
  EXPECT_DOUBLE_EQ(Get(world, 1).pose.heading.degrees(), 90.0);
  EXPECT_DOUBLE_EQ(Get(world, 0).command_remaining_s, 0.0);
  world.Step(1.0);
  EXPECT_DOUBLE_EQ(Get(world, 0).pose.position.x, 1.0);
}

TEST(PlacementTest, RandomIsInsideNonOverlappingAndSeedDependent) {
  WorldParams params;
  const double r = params.robot_radius_m;
  const std::vector<core::Pose2> poses = PlaceRandom(500, 7, params);
  ASSERT_EQ(poses.size(), 500u);
  for (std::size_t i = 0; i < poses.size(); ++i) {
    EXPECT_GE(poses[i].position.x, r);
    EXPECT_LE(poses[i].position.x, params.world_size_m - r);
    EXPECT_GE(poses[i].position.y, r);
    EXPECT_LE(poses[i].position.y, params.world_size_m - r);
    for (std::size_t j = i + 1; j < poses.size(); ++j) {
      ASSERT_GE(Dist(poses[i].position, poses[j].position), 2.0 * r * 1.1 * 1.5);
    }
  }
  const std::vector<core::Pose2> same = PlaceRandom(500, 7, params);
  const std::vector<core::Pose2> other = PlaceRandom(500, 8, params);
  ASSERT_EQ(same.size(), 500u);
  ASSERT_EQ(other.size(), 500u);
  EXPECT_EQ(same[0].position.x, poses[0].position.x);
  EXPECT_EQ(same[499].heading.degrees(), poses[499].heading.degrees());
  EXPECT_NE(other[0].position.x, poses[0].position.x);
}

TEST(PlacementTest, RandomReportsWhenRobotsDoNotFit) {
  WorldParams params;
  params.world_size_m = 1.0;
  std::string error;
  EXPECT_TRUE(PlaceRandom(500, 1, params, &error).empty());
  EXPECT_NE(error.find("cannot place 500"), std::string::npos);
  EXPECT_TRUE(PlaceRandom(0, 1, params, &error).empty());
}

TEST(PlacementTest, CornerIsAGridAtFortyFiveDegrees) {
  WorldParams params;
  const std::vector<core::Pose2> poses = PlaceCorner(10, params);
  ASSERT_EQ(poses.size(), 10u);
  EXPECT_NEAR(poses[0].position.x, 0.1, kTol);
  EXPECT_NEAR(poses[0].position.y, 0.1, kTol);
  EXPECT_NEAR(poses[1].position.x, 0.25, kTol);  // spacing 3 r
  EXPECT_NEAR(poses[4].position.y, 0.25, kTol);  // 4 columns for 10 robots
  for (const core::Pose2& p : poses) EXPECT_DOUBLE_EQ(p.heading.degrees(), 45.0);
  std::string error;
  EXPECT_TRUE(PlaceCorner(100000, params, &error).empty());
  EXPECT_FALSE(error.empty());
}

TEST(PlacementTest, ParsesLinesWithComments) {
  std::vector<core::Pose2> poses;
  std::string error;
  ASSERT_TRUE(ParsePlacement("# x y theta\n1 2 90\n\n  3.5 4.5 -90  # south\n", &poses, &error))
      << error;
  ASSERT_EQ(poses.size(), 2u);
  EXPECT_DOUBLE_EQ(poses[1].position.x, 3.5);
  EXPECT_DOUBLE_EQ(poses[1].heading.degrees(), 270.0);
  EXPECT_FALSE(ParsePlacement("1 2 90\n1 2\n", &poses, &error));
  EXPECT_NE(error.find("line 2"), std::string::npos);
  EXPECT_FALSE(ParsePlacement("1 2 3 4\n", &poses, &error));
  EXPECT_FALSE(ParsePlacement("1 x 3\n", &poses, &error));
  EXPECT_EQ(poses.size(), 2u);  // untouched on error
}

// NeighbourLists(range) of `world` is, for every robot, every other robot within range by a
// search over all pairs, in id order.
void ExpectNeighbourListsAreBruteForce(const World2D& world, double range) {
  const auto lists = world.NeighbourLists(range);
  ASSERT_EQ(lists.size(), world.size());
  std::size_t i = 0;
  for (const auto& a : world.robots()) {
    std::vector<std::uint16_t> expected;
    for (const auto& b : world.robots()) {
      if (b.first != a.first && Dist(a.second.pose.position, b.second.pose.position) <= range) {
        expected.push_back(b.first);
      }
    }
    EXPECT_EQ(lists[i], expected) << "robot " << a.first << " range " << range;
    ++i;
  }
}

TEST(NeighbourListsTest, EqualsBruteForceOnRandomRobots) {
  WorldParams params;
  params.push_apart = false;
  World2D world(params);
  core::Rng rng(3, 1);
  for (std::uint16_t id = 0; id < 300; ++id) {
    // Sparse ids, any overlap allowed: the query must not care.
    const core::Pose2 pose =
        MakePose(rng.Uniform(0.05, 11.0), rng.Uniform(0.05, 11.0), rng.Uniform(0.0, 360.0));
    ASSERT_TRUE(world.Spawn(static_cast<std::uint16_t>(3 * id + 1), pose, nullptr));
  }
  for (double range : {0.3, 1.0, 2.5, 20.0}) {
    ExpectNeighbourListsAreBruteForce(world, range);
  }
  for (const auto& list : world.NeighbourLists(0.0)) EXPECT_TRUE(list.empty());
}

// A crowd in a corner of a big arena (the hashed grid's cells are the range, not arena / sqrt(N),
// and many cells share a bucket): still exactly the robots within range, each once.
TEST(NeighbourListsTest, EqualsBruteForceOnACrowdInABigArena) {
  WorldParams params;
  params.push_apart = false;
  params.world_size_m = 200.0;
  World2D world(params);
  core::Rng rng(5, 2);
  for (std::uint16_t id = 0; id < 500; ++id) {
    const core::Pose2 pose =
        MakePose(rng.Uniform(0.05, 2.5), rng.Uniform(0.05, 2.5), rng.Uniform(0.0, 360.0));
    ASSERT_TRUE(world.Spawn(id, pose, nullptr));
  }
  for (double range : {0.1, 0.35, 1.0}) {
    ExpectNeighbourListsAreBruteForce(world, range);
  }
}

}  // namespace
}  // namespace sim
}  // namespace swarm_transport
