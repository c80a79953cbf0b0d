#include "swarm_transport/core/command_echo.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr double kDt = 0.1;

Pose2 At(double x, double y, double heading_deg) { return Pose2{{x, y}, Angle(heading_deg)}; }

TEST(CommandEchoTest, ARoundThatShowsTheTurnIsTakenAsItIs) {
  CommandEcho echo;
  const Pose2 from = At(5.0, 5.0, 0.0);
  const Velocity command = CommandFor(from, Angle(90.0), 0.1, kDt);
  echo.Sent(from, command, kDt);
  const Pose2 shown = TurnThenDrive(from, command, kDt);
  const Pose2 plan = echo.PlanFrom(shown);
  EXPECT_NEAR(plan.position.x, shown.position.x, 1e-12);
  EXPECT_NEAR(plan.heading.degrees(), 90.0, 1e-9);
  EXPECT_EQ(echo.unseen(), 0u);
}

TEST(CommandEchoTest, ARoundMadeBeforeTheCommandArrivedIsAdvancedByIt) {
  CommandEcho echo;
  const Pose2 from = At(5.0, 5.0, 0.0);
  const Velocity command = CommandFor(from, Angle(90.0), 0.1, kDt);
  echo.Sent(from, command, kDt);
  // The round shows it where it was (its previous command drove it a little, no turn).
  const Pose2 shown = At(5.02, 5.0, 0.5);
  const Pose2 plan = echo.PlanFrom(shown);
  EXPECT_EQ(echo.unseen(), 1u);
  EXPECT_NEAR(plan.heading.degrees(), 90.5, 1e-9);
  // Then it drives its 0.1 m along 90.5 degrees.
  EXPECT_NEAR(plan.position.x, 5.02 + 0.1 * std::cos(90.5 * M_PI / 180.0), 1e-9);
  EXPECT_NEAR(plan.position.y, 5.0 + 0.1 * std::sin(90.5 * M_PI / 180.0), 1e-9);
  // Each command counts once: the next round is taken as it is.
  const Pose2 again = echo.PlanFrom(shown);
  EXPECT_NEAR(again.heading.degrees(), 0.5, 1e-9);
  EXPECT_EQ(echo.unseen(), 1u);
}

TEST(CommandEchoTest, ASmallTurnOrAForgottenCommandTellsNothing) {
  CommandEcho echo;
  const Pose2 from = At(5.0, 5.0, 10.0);
  echo.Sent(from, CommandFor(from, Angle(11.0), 0.1, kDt), kDt);
  EXPECT_NEAR(echo.PlanFrom(from).heading.degrees(), 10.0, 1e-9);
  echo.Sent(from, CommandFor(from, Angle(100.0), 0.1, kDt), kDt);
  echo.Forget();
  EXPECT_NEAR(echo.PlanFrom(from).heading.degrees(), 10.0, 1e-9);
  EXPECT_EQ(echo.unseen(), 0u);
}

// A leader's loop against the simulator's world when every round is made before the command of
// the round before arrived (a robot that ticks just before the simulator steps): steering for
// the goal from the round's pose as it is, its heading swings and it never arrives; planning
// from CommandEcho's pose, it drives to the goal.
double DistanceAfterLaggedLoop(bool echo_on, int ticks) {
  sim::WorldParams params;
  params.command_duration_s = kDt;
  sim::World2D world(params);
  std::string error;
  EXPECT_TRUE(world.Spawn(0, At(2.0, 2.0, 180.0), &error)) << error;
  const Vec2 goal{8.0, 8.0};
  CommandEcho echo;
  Velocity in_transit;
  bool have_in_transit = false;
  for (int t = 0; t < ticks; ++t) {
    const Pose2 round = world.Find(0)->pose;  // made before the command in transit arrives
    if (have_in_transit) EXPECT_TRUE(world.SetCommand(0, in_transit, &error)) << error;
    const Pose2 from = echo_on ? echo.PlanFrom(round) : round;
    const double to_goal = Distance(from.position, goal);
    const Velocity command =
        CommandFor(from, Bearing(from.position, goal), std::min(0.1, to_goal), kDt);
    echo.Sent(from, command, kDt);
    in_transit = command;
    have_in_transit = true;
    world.Step(kDt);
  }
  return Distance(world.Find(0)->pose.position, goal);
}

TEST(CommandEchoTest, ALeaderOneCommandBehindArrivesOnlyWithIt) {
  // 8.5 m at 0.1 m per tick: 150 ticks are ample for a robot that heads for its goal. Without
  // the echo it ends 11.2 m from it, near the arena's corner (0, 0) (measured when written).
  EXPECT_LT(DistanceAfterLaggedLoop(true, 150), 0.2);
  EXPECT_GT(DistanceAfterLaggedLoop(false, 150), 1.0);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
