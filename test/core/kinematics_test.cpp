#include "swarm_transport/core/kinematics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <stdexcept>

#include "swarm_transport/core/random.h"

namespace swarm_transport {
namespace core {
namespace {

constexpr double kTolerance = 1e-9;

void ExpectNear(Vec2 actual, Vec2 expected) {
  EXPECT_NEAR(actual.x, expected.x, kTolerance);
  EXPECT_NEAR(actual.y, expected.y, kTolerance);
}

TEST(KinematicsTest, ZeroTurnRateDrivesAStraightLine) {
  const Pose2 end = Integrate({{1.0, 2.0}, Angle(90)}, {0.5, 0.0}, 2.0);
  ExpectNear(end.position, {1.0, 3.0});
  EXPECT_EQ(end.heading, Angle(90));
}

TEST(KinematicsTest, QuarterCircleLeftEndsAtRadiusOffsets) {
  // Radius v / w = 1: a left quarter circle from the origin facing +x ends at (1, 1) facing +y.
  const Pose2 end = Integrate({{0.0, 0.0}, Angle(0)}, {M_PI / 2, M_PI / 2}, 1.0);
  ExpectNear(end.position, {1.0, 1.0});
  EXPECT_EQ(end.heading, Angle(90));
}

TEST(KinematicsTest, QuarterCircleRightEndsBelow) {
  const Pose2 end = Integrate({{0.0, 0.0}, Angle(0)}, {M_PI / 2, -M_PI / 2}, 1.0);
  ExpectNear(end.position, {1.0, -1.0});
  EXPECT_EQ(end.heading, Angle(270));
}

TEST(KinematicsTest, IntegrationComposes) {
  const Pose2 start{{3.0, 4.0}, Angle(200)};
  const Velocity velocity{0.3, 0.7};
  const Pose2 in_two = Integrate(Integrate(start, velocity, 0.4), velocity, 0.9);
  const Pose2 in_one = Integrate(start, velocity, 1.3);
  ExpectNear(in_two.position, in_one.position);
  EXPECT_EQ(in_two.heading, in_one.heading);
}

TEST(KinematicsTest, IntegrateWithTrigCacheIsBitIdentical) {
  // Sub-steps of straight drives, turns between them, arcs, and a cache left by another robot:
  // the cached version always gives Integrate's very doubles.
  Rng rng(7, 1);
  HeadingTrig trig;
  Pose2 plain{{1.0, 2.0}, Angle(30.0)};
  Pose2 cached = plain;
  for (int step = 0; step < 2000; ++step) {
    if (step % 50 == 0) {
      const Angle turn = Angle(rng.Uniform(-180.0, 180.0));
      plain.heading = plain.heading + turn;
      cached.heading = cached.heading + turn;
    }
    if (step % 333 == 0) trig = HeadingTrig{rng.Uniform(-3.0, 3.0), 0.5, 0.5, true};  // stale
    const Velocity v{rng.Uniform(0.0, 0.2), step % 7 == 0 ? rng.Uniform(-1.0, 1.0) : 0.0};
    const double d = rng.Uniform(0.001, 0.02);
    plain = Integrate(plain, v, d);
    cached = Integrate(cached, v, d, &trig);
    ASSERT_EQ(plain.position.x, cached.position.x) << step;
    ASSERT_EQ(plain.position.y, cached.position.y) << step;
    ASSERT_EQ(plain.heading.degrees(), cached.heading.degrees()) << step;
  }
}

TEST(KinematicsTest, CommandForEndsAtTheRequestedHeading) {
  const Pose2 start{{5.0, 5.0}, Angle(350)};
  const Velocity command = CommandFor(start, Angle(20), 0.3, 2.0);
  EXPECT_NEAR(command.angular, (30.0 * M_PI / 180.0) / 2.0, kTolerance);
  EXPECT_NEAR(command.linear, 0.15, kTolerance);
  EXPECT_EQ(Integrate(start, command, 2.0).heading, Angle(20));
}

TEST(KinematicsTest, CommandForTurnsTheShortWay) {
  const Velocity command = CommandFor({{0.0, 0.0}, Angle(10)}, Angle(350), 0.1, 1.0);
  EXPECT_NEAR(command.angular, -20.0 * M_PI / 180.0, kTolerance);
}

TEST(KinematicsTest, CommandForStepBackTurnsHalfACircle) {
  const Velocity command = CommandFor({{0.0, 0.0}, Angle(0)}, Angle(180), 0.1, 1.0);
  EXPECT_NEAR(command.angular, M_PI, kTolerance);
}

TEST(KinematicsTest, CommandForWithoutTurnDrivesTheDistance) {
  const Pose2 start{{1.0, 1.0}, Angle(45)};
  const Pose2 end = Integrate(start, CommandFor(start, Angle(45), 0.2, 1.0), 1.0);
  EXPECT_NEAR(Distance(start.position, end.position), 0.2, kTolerance);
}

TEST(KinematicsTest, CommandForRejectsNonPositiveDuration) {
  EXPECT_THROW(CommandFor({}, Angle(0), 0.1, 0.0), std::invalid_argument);
}

TEST(KinematicsTest, SampleArcRunsFromStartToDestination) {
  const Pose2 start{{2.0, 3.0}, Angle(30)};
  const Velocity velocity{0.2, 0.5};
  const std::vector<Vec2> samples = SampleArc(start, velocity, 2.0, 5);
  ASSERT_EQ(samples.size(), 5u);
  ExpectNear(samples.front(), start.position);
  ExpectNear(samples[2], Integrate(start, velocity, 1.0).position);
  ExpectNear(samples.back(), Integrate(start, velocity, 2.0).position);
}

TEST(KinematicsTest, SampleArcNeedsTwoSamples) {
  EXPECT_THROW(SampleArc({}, {0.1, 0.0}, 1.0, 1), std::invalid_argument);
}

}  // namespace
TEST(TurnThenDriveTest, TurnsFirstThenDrivesAlongTheNewHeading) {
  const Pose2 start{{2.0, 3.0}, Angle(350.0)};
  // +20 degrees of turn and 0.5 m within 0.1 s.
  const Velocity v = CommandFor(start, Angle(10.0), 0.5, 0.1);
  const Pose2 end = TurnThenDrive(start, v, 0.1);
  EXPECT_EQ(end.heading, Angle(10.0));
  EXPECT_NEAR(end.position.x, 2.0 + 0.5 * std::cos(10.0 * M_PI / 180.0), 1e-12);
  EXPECT_NEAR(end.position.y, 3.0 + 0.5 * std::sin(10.0 * M_PI / 180.0), 1e-12);
}

}  // namespace core
}  // namespace swarm_transport
