// conversions.h: the one place that knows messages and core types. Round trips keep what the
// wire can carry (float32), angles land in the ranges the messages promise, and every non-finite
// float is caught by the checks that guard each subscriber.
#include "swarm_transport/ros/common/conversions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "../core/fixtures.h"

namespace swarm_transport {
namespace {

constexpr double kFloatTol = 1e-5;
const float kNan = std::numeric_limits<float>::quiet_NaN();

TEST(ConversionsTest, RobotPositionRoundTripKeepsPoseAndIdentity) {
  const core::Pose2 pose{{3.25, 7.5}, core::Angle(123.0)};
  const Robot_Position msg = ToRobotPosition(42, pose, 3, Robot_Position::TYPE_VIRTUAL);
  EXPECT_EQ(msg.robot_id, 42);
  EXPECT_EQ(msg.sub_id, 3);
  EXPECT_EQ(msg.type, Robot_Position::TYPE_VIRTUAL);
  const core::Neighbour n = ToNeighbour(msg);
  EXPECT_EQ(n.id, 42);
  EXPECT_EQ(n.sub_id, 3);
  EXPECT_EQ(n.type, Robot_Position::TYPE_VIRTUAL);
  EXPECT_NEAR(n.position.x, 3.25, kFloatTol);
  EXPECT_NEAR(n.position.y, 7.5, kFloatTol);
  EXPECT_NEAR(n.heading.degrees(), 123.0, 1e-4);
}

// A leader's announced virtual copies (SPEC 9.2) ride on its own position and on its answer.
TEST(ConversionsTest, AnnouncedCopiesTravelOnPositionsAndAnswers) {
  core::Position own = core::PositionOf(7, {{1.0, 2.0}, core::Angle(10.0)});
  own.copies = 4;
  const Robot_Position msg = ToRobotPosition(own);
  EXPECT_EQ(msg.copies, 4);
  EXPECT_EQ(ToPosition(msg).copies, 4);
  EXPECT_EQ(ToNeighbour(msg).copies, 4);
  Robot_Position statist = msg;
  statist.type = Robot_Position::TYPE_STATIST;
  EXPECT_EQ(ToNeighbour(statist).copies, 0) << "only a robot's own position announces copies";
  core::Answer answer;
  answer.copies = 9;
  const Tick_Answer wire = ToTickAnswer(answer, ros::Time(1.0));
  EXPECT_EQ(wire.copies, 9);
  EXPECT_EQ(ToAnswer(wire).copies, 9);
}

TEST(ConversionsTest, RobotPositionAngleStaysBelow360AfterFloatRounding) {
  // 360 - 1e-9 degrees rounds to 360.0f as float: the message promises [0, 360).
  const Robot_Position msg = ToRobotPosition(1, {{1.0, 1.0}, core::Angle(360.0 - 1e-9)});
  EXPECT_GE(msg.angle, 0.0f);
  EXPECT_LT(msg.angle, 360.0f);
}

TEST(ConversionsTest, PoseThetaIsInMinusPiToPi) {
  const Pose msg = ToPoseMsg({{2.0, 3.0}, core::Angle(270.0)}, core::Velocity{0.5, -0.25});
  EXPECT_NEAR(msg.theta, -M_PI / 2.0, kFloatTol);
  EXPECT_NEAR(msg.linear_velocity, 0.5, kFloatTol);
  EXPECT_NEAR(msg.angular_velocity, -0.25, kFloatTol);
  const core::Pose2 back = ToPose2(msg);
  EXPECT_NEAR(back.heading.degrees(), 270.0, 1e-4);
  EXPECT_NEAR(ToPoseMsg({{0.0, 0.0}, core::Angle(180.0)}, {}).theta, M_PI, kFloatTol);
}

TEST(ConversionsTest, TwistCarriesLinearXAndAngularZ) {
  const geometry_msgs::Twist t = ToTwist(core::Velocity{0.1, 1.5});
  EXPECT_DOUBLE_EQ(t.linear.x, 0.1);
  EXPECT_DOUBLE_EQ(t.angular.z, 1.5);
  EXPECT_DOUBLE_EQ(t.linear.y, 0.0);
  const core::Velocity v = ToVelocity(t);
  EXPECT_DOUBLE_EQ(v.linear, 0.1);
  EXPECT_DOUBLE_EQ(v.angular, 1.5);
}

TEST(ConversionsTest, EveryNonFiniteFloatIsCaught) {
  Robot_Position p = ToRobotPosition(1, {{1.0, 1.0}, core::Angle(0.0)});
  EXPECT_TRUE(IsFinite(p));
  for (float Robot_Position::*field :
       {&Robot_Position::pos_x, &Robot_Position::pos_y, &Robot_Position::angle}) {
    Robot_Position bad = p;
    bad.*field = kNan;
    EXPECT_FALSE(IsFinite(bad));
  }
  geometry_msgs::Twist t;
  EXPECT_TRUE(IsFinite(t));
  for (double* field :
       {&t.linear.x, &t.linear.y, &t.linear.z, &t.angular.x, &t.angular.y, &t.angular.z}) {
    const double old = *field;
    *field = std::numeric_limits<double>::infinity();
    EXPECT_FALSE(IsFinite(t));
    *field = old;
  }
}

TEST(ConversionsTest, MissionRoundTripKeepsTheOrder) {
  core::MissionSpec spec = core::fixtures::Thesis(7);
  spec.range_to = 12;
  spec.leader_number = 3;
  spec.transport_mode = New_Mission::MODE_FORMATION;
  const New_Mission msg = ToNewMission(spec);
  EXPECT_EQ(msg.start_tick, 0u);  // a spec has no start tick: the dispatcher stamps it
  const core::MissionSpec back = ToMissionSpec(msg);
  EXPECT_EQ(back.id, 7);
  EXPECT_EQ(back.Assigned().size(), 12u);
  EXPECT_EQ(back.Leaders(), (std::vector<std::uint16_t>{0, 1, 2}));
  EXPECT_EQ(back.transport_mode, New_Mission::MODE_FORMATION);
  EXPECT_DOUBLE_EQ(back.target.x, 3.0);
  EXPECT_TRUE(back.all_finite);
  spec.robot_ids = {9, 4, 4};
  EXPECT_EQ(ToMissionSpec(ToNewMission(spec)).Assigned(), (std::vector<std::uint16_t>{4, 9}));
  EXPECT_TRUE(msg.leader_ids.empty());  // none named: the lowest lead, as before
  spec.leader_number = 1;
  spec.leader_ids = {9};  // (ext) named leaders, e.g. a count-only mission's front robot
  EXPECT_EQ(ToNewMission(spec).leader_ids, (std::vector<std::uint16_t>{9}));
  EXPECT_EQ(ToMissionSpec(ToNewMission(spec)).Leaders(), (std::vector<std::uint16_t>{9}));
}

TEST(ConversionsTest, AMissionWithANonFiniteFloatIsMarked) {
  New_Mission msg;
  msg.mission_id = 1;
  msg.robot_index_to = 2;
  msg.leader_number = 1;
  EXPECT_TRUE(ToMissionSpec(msg).all_finite);
  for (float New_Mission::*field :
       {&New_Mission::object_position_x, &New_Mission::object_position_y,
        &New_Mission::object_size_x, &New_Mission::object_size_y, &New_Mission::target_x,
        &New_Mission::target_y}) {
    New_Mission bad = msg;
    bad.*field = kNan;
    EXPECT_FALSE(ToMissionSpec(bad).all_finite);
  }
}

TEST(ConversionsTest, LeaderNumberIsClampedToTheWire) {
  core::MissionSpec spec;
  spec.leader_number = 300;
  EXPECT_EQ(ToNewMission(spec).leader_number, 255);
  spec.leader_number = -4;
  EXPECT_EQ(ToNewMission(spec).leader_number, 0);
}

TEST(ConversionsTest, SenderOfTellsTheDispatcherRelaysRobotsAndOthers) {
  EXPECT_EQ(SenderOf("/mission_dispatcher").kind, core::SenderKind::kDispatcher);
  EXPECT_EQ(SenderOf("/simulator").kind, core::SenderKind::kRelay);
  EXPECT_EQ(SenderOf("/robot_host").kind, core::SenderKind::kRelay);
  EXPECT_EQ(SenderOf("/robot_host_b").kind, core::SenderKind::kRelay);
  const core::Sender robot = SenderOf("/robot_17/robot");
  EXPECT_EQ(robot.kind, core::SenderKind::kRobot);
  EXPECT_EQ(robot.robot_id, 17);
  EXPECT_EQ(SenderOf("/robot_65535/robot").robot_id, 65535);
  for (const char* other :
       {"/robot_65536/robot", "/robot_/robot", "/robot_1x/robot", "/robot_3/robotx", "/robot_3",
        "/rostopic_123_456", "/mission_dispatcher_2", "", "/robot_-1/robot"}) {
    EXPECT_EQ(SenderOf(other).kind, core::SenderKind::kOther) << other;
  }
}

TEST(ConversionsTest, FlockingTuningRoundTripKeepsEveryValue) {
  core::FlockingTuning t;
  t.free_will_deg = 45.5;
  t.cohesion = -0.25;
  t.local_range_m = 1.75;
  t.speed_m_per_tick = 0.125;
  const Flocking_Tuning msg = ToTuningMsg(t, 3, 42);
  EXPECT_EQ(msg.generation, 3u);
  EXPECT_EQ(msg.tick, 42u);
  EXPECT_TRUE(ToFlockingTuning(msg) == t);
}

}  // namespace
}  // namespace swarm_transport
