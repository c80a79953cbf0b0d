// robot_report.h: a robot's ~state and ~describe say the pose it planned from and the object it
// carries, so that a mission found standing can be read from them (a soak's hung mission).
#include "swarm_transport/ros/robot/robot_report.h"

#include <gtest/gtest.h>

#include <string>

#include "../core/fixtures.h"

namespace swarm_transport {
namespace {

core::SwarmConfig Config() {
  core::SwarmConfig c;
  c.flocking.local_range_m = 1.0;
  c.flocking.speed_m_per_tick = 0.1;
  c.tick_period_s = 1.0;
  c.seed = 3;
  return c;
}

core::Perception At(double x, double y, double heading_deg) {
  core::Perception in;
  in.self = {{x, y}, core::Angle(heading_deg)};
  return in;
}

TEST(RobotReportTest, AFlockingRobotSaysThePoseItPlannedFromAndNoObject) {
  core::RobotSession session(2, Config());
  session.Tick(At(1.5, 2.25, 30.0), 1, 1.0, true);
  const Robot_State::Response s = StateOf(session, 1, true);
  EXPECT_DOUBLE_EQ(s.x, 1.5);
  EXPECT_DOUBLE_EQ(s.y, 2.25);
  EXPECT_NEAR(s.theta_deg, 30.0, 1e-9);
  EXPECT_FALSE(s.carrying);
  // What only the node knows (its round's age, its command's listeners) is unknown here.
  EXPECT_DOUBLE_EQ(s.round_age_s, -1.0);
  EXPECT_EQ(s.command_listeners, -1);
  std::string text = Describe(s);
  EXPECT_EQ(text.find("round_age="), std::string::npos) << text;
  Robot_State::Response known = s;
  known.round_age_s = 0.25;
  known.command_listeners = 1;
  known.round_waits = 3;
  known.late_command_rounds = 2;
  EXPECT_NE(Describe(known).find(" round_age=0.25 round_waits=3 late_cmd_rounds=2 cmd_listeners=1"),
            std::string::npos)
      << Describe(known);
  text = Describe(s);
  EXPECT_NE(text.find(" at=(1.5, 2.25, 30)"), std::string::npos) << text;
  EXPECT_EQ(text.find("object="), std::string::npos) << text;
}

TEST(RobotReportTest, AMissionRobotSaysItsObjectItsTargetAndWhetherItIsInside) {
  // Member 1 of the thesis mission (2 x 2 object at (7, 7) to (3, 3)), once inside, once out.
  for (const bool inside : {true, false}) {
    core::RobotSession session(1, Config());
    const core::RobotSession::Taken taken = session.Take(
        core::fixtures::Thesis(), core::Sender{core::SenderKind::kDispatcher, 0}, {0, 1, 2});
    ASSERT_EQ(taken.why, "");
    const double x = inside ? 7.5 : 2.0;
    session.Tick(At(x, 7.0, 0.0), 1, 1.0, true);
    const Robot_State::Response s = StateOf(session, 1, true);
    EXPECT_DOUBLE_EQ(s.x, x);
    ASSERT_TRUE(s.carrying);
    EXPECT_DOUBLE_EQ(s.target_x, 3.0);
    EXPECT_DOUBLE_EQ(s.target_y, 3.0);
    EXPECT_EQ(s.inside, inside);
    const std::string text = Describe(s);
    EXPECT_NE(text.find("->(3, 3) inside=" + std::string(inside ? "1" : "0")), std::string::npos)
        << text;
  }
}

}  // namespace
}  // namespace swarm_transport
