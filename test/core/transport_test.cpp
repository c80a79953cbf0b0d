// Carrying: gathering, the thesis's swarm transport (leaders bound to the current object,
// outside -> centre, passive look-ahead) and formation transport.
#include "swarm_transport/core/transport.h"

#include <gtest/gtest.h>

#include <cmath>

#include "fixtures.h"
#include "swarm_transport/core/kinematics.h"

namespace swarm_transport {
namespace core {
namespace {

using fixtures::At;
using fixtures::Quiet;

constexpr double kTick = 1.0;

// Robot 1 at (x, y) heading `deg` carrying a 2x2 object centred at `centre` to (3, 3).
struct Scene {
  Perception in;
  Carry carry;
};
Scene Carrying(double x, double y, double deg, Vec2 centre, bool leader) {
  Scene s;
  s.in.self_id = 1;
  s.in.self = {{x, y}, Angle(deg)};
  s.carry.transport = true;
  s.carry.leader = leader;
  s.carry.centre = centre;
  s.carry.object = Shape::FromRect(centre, {2.0, 2.0});
  s.carry.target = {3.0, 3.0};
  s.in.group.only = true;
  s.in.group.ids = {1, 2, 3};
  return s;
}

Vec2 Destination(const Perception& in, const MoveDecision& d) {
  return TurnThenDrive(in.self, CommandFor(in.self, d.heading, d.distance_m, kTick), kTick)
      .position;
}

TEST(TransportParamsTest, DefaultsAreValidAndBadValuesNamed) {
  EXPECT_EQ(TransportParams().Validate(), "");
  TransportParams p;
  p.leader_slowdown = 1.0;
  EXPECT_EQ(p.Validate(), "leader_slowdown must be in (0, 1) but is 1");
  p = TransportParams();
  p.formation_speed_fraction = 0.0;
  EXPECT_EQ(p.Validate(), "formation_speed_fraction must be in (0, 1] but is 0");
  GatherMode g = GatherMode::kFill;
  EXPECT_TRUE(ParseGatherMode("hold", &g));
  EXPECT_EQ(g, GatherMode::kHold);
  EXPECT_FALSE(ParseGatherMode("wander", &g));
}

TEST(CarryStepTest, ALeaderIsBoundToTheCurrentObject) {
  // Leader 0.05 inside the south-west corner of the object at (7, 7), course 225 degrees: at
  // 0.1 and at 0.075 per tick it would leave the object (each axis moves 0.071, 0.053 > 0.05);
  // at 0.75^2 x 0.1 (0.040 per axis) it stays inside.
  Scene s = Carrying(6.05, 6.05, 0.0, {7.0, 7.0}, true);
  Rng rng(1, 1);
  const MoveDecision d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kSlowed);
  EXPECT_NEAR(d.heading.degrees(), 225.0, 1e-9);
  EXPECT_NEAR(d.distance_m, 0.1 * 0.75 * 0.75, 1e-12);
  EXPECT_TRUE(s.carry.object.Contains(Destination(s.in, d)));
}

TEST(CarryStepTest, ABlockedLeaderTurnsToItsCourseAndHolds) {
  // On the border itself: no speed keeps it inside; it faces 225 degrees and stands.
  Scene s = Carrying(6.0, 7.0, 90.0, {7.0, 7.0}, true);
  s.carry.target = {3.0, 7.0};  // course 180: straight out of the west border
  Rng rng(1, 1);
  const MoveDecision d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kStand);
  EXPECT_DOUBLE_EQ(d.distance_m, 0.0);
  EXPECT_NEAR(d.heading.degrees(), 180.0, 1e-9);
  // Unbound, it drives on.
  TransportParams unbound;
  unbound.leaders_bound = false;
  const MoveDecision free = CarryStep(s.in, Quiet(), unbound, s.carry, rng, kTick);
  EXPECT_EQ(free.outcome, MoveOutcome::kStraight);
  EXPECT_DOUBLE_EQ(free.distance_m, 0.1);
}

TEST(CarryStepTest, ARobotWedgedAtTheRimGoesRoundToGetIn) {
  // Just outside the south border, two robots holding inside block the way in: it may move
  // along or away from the rim (no safety zone holds it) rather than stand for good.
  Scene s = Carrying(6.226, 5.963, 172.0, {7.0, 7.0}, false);
  s.carry.transport = false;
  s.in.others = {At(4, 6.161, 6.052), At(7, 6.313, 6.050)};
  Rng rng(1, 1);
  const MoveDecision d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kSwerved);
  EXPECT_GT(d.distance_m, 0.0);
}

TEST(CarryStepTest, AnyRobotOutsideDrivesStraightForTheCentre) {
  for (const bool leader : {false, true}) {
    Scene s = Carrying(9.0, 7.0, 0.0, {7.0, 7.0}, leader);
    s.in.others = {At(2, 7.0, 7.3, 90.0)};  // a heading to align with: it must not
    Rng rng(1, 1);
    FlockingParams p = Quiet();
    p.free_will_deg = 90.0;
    const MoveDecision d = CarryStep(s.in, p, TransportParams(), s.carry, rng, kTick);
    EXPECT_NEAR(d.heading.degrees(), 180.0, 1e-9) << leader;
    EXPECT_DOUBLE_EQ(d.distance_m, 0.1);
  }
}

TEST(CarryStepTest, APassiveRobotKeepsItsLookAheadPointInside) {
  // Heading east (its chain's mean) 0.1 from the east border: 1.5 steps ahead is outside, so
  // it swerves until the point 0.15 ahead is inside: cos(h) * 0.15 <= 0.1.
  Scene s = Carrying(7.9, 7.0, 0.0, {7.0, 7.0}, false);
  s.in.others = {At(2, 7.6, 7.0, 0.0)};
  Rng rng(1, 1);
  const MoveDecision d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kSwerved);
  EXPECT_NEAR(d.distance_m, 0.1, 1e-12);
  const Vec2 ahead = s.in.self.position + UnitVector(d.heading) * 0.15;
  EXPECT_TRUE(s.carry.object.Contains(ahead));
  EXPECT_GE(std::fabs(d.heading.degrees() > 180 ? d.heading.degrees() - 360 : d.heading.degrees()),
            std::acos(0.1 / 0.15) * 180.0 / M_PI - 1.0);
}

TEST(CarryStepTest, GatheringHoldsInsideOnceBlockedOrFillsTheObject) {
  Scene s = Carrying(6.5, 7.0, 0.0, {7.0, 7.0}, false);
  s.carry.transport = false;
  Rng rng(1, 1);
  // Inside and free: straight on for the centre (the rim stays free for late-comers).
  const MoveDecision in = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(in.outcome, MoveOutcome::kStraight);
  EXPECT_NEAR(in.heading.degrees(), 0.0, 1e-9);
  // Blocked on the way: it holds, it does not swerve.
  s.in.others = {At(2, 6.65, 7.0)};
  EXPECT_EQ(CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick).outcome,
            MoveOutcome::kStand);
  TransportParams fill;
  fill.gathering = GatherMode::kFill;
  EXPECT_GT(CarryStep(s.in, Quiet(), fill, s.carry, rng, kTick).distance_m, 0.0);
}

TEST(CarryStepTest, GatheringToASlotDrivesForItSwervesAroundRobotsAndStandsOnIt) {
  // Outside the object (7, 7), its slot at (6.2, 6.25): straight for the slot, not the centre.
  Scene s = Carrying(5.0, 6.25, 90.0, {7.0, 7.0}, false);
  s.carry.transport = false;
  s.carry.slot = Vec2{6.2, 6.25};
  Rng rng(1, 1);
  MoveDecision d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kStraight);
  EXPECT_NEAR(d.heading.degrees(), 0.0, 1e-9);
  EXPECT_NEAR(d.distance_m, 0.1, 1e-9);
  // A robot in the way: it swerves (hold would stand inside; nearest drives for the centre).
  s.in.others = {At(2, 5.15, 6.25)};
  d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kSwerved);
  EXPECT_GT(d.distance_m, 0.0);
  // The last bit: only as far as the slot; on it, it stands.
  s.in.others.clear();
  s.in.self.position = {6.15, 6.25};
  d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_NEAR(d.distance_m, 0.05, 1e-9);
  s.in.self.position = {6.2, 6.25};
  EXPECT_EQ(CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick).outcome,
            MoveOutcome::kStand);
  // A leader on its slot faces its course (225 degrees to (3, 3)).
  s.carry.leader = true;
  d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kStand);
  EXPECT_NEAR(d.heading.degrees(), 225.0, 1e-9);
}

TEST(CarryStepTest, InsideTheObjectASlotRobotSwervesOnlyOntoMovesThatStayInside) {
  // 0.02 inside the south rim of the object (7, 7), its slot east along the rim, a robot in
  // the way east: it swerves north, into the object.
  Scene s = Carrying(7.0, 6.02, 0.0, {7.0, 7.0}, false);
  s.carry.transport = false;
  s.carry.slot = Vec2{7.8, 6.02};
  s.in.others = {At(2, 7.1, 6.02)};
  Rng rng(1, 1);
  MoveDecision d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kSwerved);
  EXPECT_TRUE(s.carry.object.Contains(Destination(s.in, d)));
  // Robots 0.12 away every 30 degrees from east round to west wall off every move inside; the
  // first free swerve leads out under the rim: it stands instead.
  s.in.others.clear();
  for (int k = 0; k <= 6; ++k) {
    const double a = k * 30.0 * M_PI / 180.0;
    s.in.others.push_back(
        At(static_cast<std::uint16_t>(2 + k), 7.0 + 0.12 * std::cos(a), 6.02 + 0.12 * std::sin(a)));
  }
  d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kStand);
  EXPECT_DOUBLE_EQ(d.distance_m, 0.0);
}

TEST(TransportParamsTest, GatherPlannerNamesAndBadPlannerValues) {
  GatherPlanner g = GatherPlanner::kNearest;
  for (const char* name : {"nearest", "selection_matrix", "optimal", "bottleneck", "row_minimum"}) {
    ASSERT_TRUE(ParseGatherPlanner(name, &g)) << name;
    EXPECT_STREQ(GatherPlannerName(g), name);
  }
  EXPECT_FALSE(ParseGatherPlanner("closest", &g));
  EXPECT_EQ(g, GatherPlanner::kRowMinimum);  // unchanged by a bad name
  TransportParams p;
  EXPECT_EQ(p.gather_planner, GatherPlanner::kNearest);  // the default keeps the thesis's way
  p.replan_period_ticks = 0;
  EXPECT_EQ(p.Validate(), "replan_period must be >= 1 (ticks) but is 0");
  p = TransportParams();
  p.planner_turn_deg_per_tick = 0.0;
  EXPECT_EQ(p.Validate(), "planner_turn_deg_per_tick must be finite and > 0 but is 0");
}

TEST(CarryStepTest, EveryBranchDrawsOneSample) {
  Scene inside = Carrying(7.0, 7.0, 0.0, {7.0, 7.0}, false);
  Scene outside = Carrying(9.0, 9.0, 0.0, {7.0, 7.0}, true);
  Rng a(5, 5);
  Rng b(5, 5);
  CarryStep(inside.in, Quiet(), TransportParams(), inside.carry, a, kTick);
  CarryStep(outside.in, Quiet(), TransportParams(), outside.carry, b, kTick);
  EXPECT_EQ(a.Uniform(0.0, 1.0), b.Uniform(0.0, 1.0));
}

TEST(CarryStepTest, ALeaderJustOutsideKeepsItsCourseOnlyWithinItsReach) {
  // 0.2 m west of the object (7, 7), course 180 (straight further out): by default (the
  // evaluated code) it drives for the centre; with a reach of 0.5 m it faces its course and
  // holds (its course would take it farther out).
  Scene s = Carrying(5.8, 7.0, 90.0, {7.0, 7.0}, true);
  s.carry.target = {3.0, 7.0};
  Rng rng(1, 1);
  const MoveDecision in = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_NEAR(in.heading.degrees(), 0.0, 1e-9);
  EXPECT_DOUBLE_EQ(in.distance_m, 0.1);
  TransportParams reach;
  reach.leader_reach_m = 0.5;
  const MoveDecision held = CarryStep(s.in, Quiet(), reach, s.carry, rng, kTick);
  EXPECT_EQ(held.outcome, MoveOutcome::kStand);
  EXPECT_NEAR(held.heading.degrees(), 180.0, 1e-9);
  // A course about along the border, slightly inwards (80.5 degrees): it drives on.
  s.carry.target = {7.5, 10.0};
  const MoveDecision along = CarryStep(s.in, Quiet(), reach, s.carry, rng, kTick);
  EXPECT_GT(along.distance_m, 0.0);
  EXPECT_LE(s.carry.object.DistanceTo(Destination(s.in, along)), 0.2 + 1e-9);
}

TEST(CarryStepTest, ALeaderUnderItsObjectFacesItsCourseWhenItStands) {
  // Gathering, blocked on its way to the centre: it stands facing the course (225 degrees),
  // not where it came from; while loading (frozen) it turns to the course even with the way
  // free.
  Scene s = Carrying(6.5, 7.0, 0.0, {7.0, 7.0}, true);
  s.carry.transport = false;
  s.in.others = {At(2, 6.65, 7.0)};
  Rng rng(1, 1);
  MoveDecision d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kStand);
  EXPECT_NEAR(d.heading.degrees(), 225.0, 1e-9);
  s.in.others.clear();
  s.carry.loading = true;
  d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_EQ(d.outcome, MoveOutcome::kStand);
  EXPECT_NEAR(d.heading.degrees(), 225.0, 1e-9);
  // A passive robot keeps its heading; so does a leader with the option off.
  TransportParams off;
  off.leaders_face_course = false;
  s.in.others = {At(2, 6.65, 7.0)};
  s.carry.loading = false;
  EXPECT_NEAR(CarryStep(s.in, Quiet(), off, s.carry, rng, kTick).heading.degrees(), 0.0, 1e-9);
  s.carry.leader = false;
  EXPECT_NEAR(CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick).heading.degrees(),
              0.0, 1e-9);
}

TEST(CarryStepTest, APassiveRobotWeighsItsLeadersHeadingsKTimes) {
  // Itself heading 0, leader 2 heading 180, passive 3 heading 90 (no free will, no cohesion):
  // alone the vectors sum to (0, 1) -> 90 degrees; with the leader counted 3 times to (-2, 1)
  // -> 153.4 degrees. Only the robots count as its neighbourhood.
  Scene s = Carrying(7.0, 7.0, 0.0, {7.0, 7.0}, false);
  s.carry.leaders = {2};
  s.in.others = {At(2, 7.3, 7.0, 180.0), At(3, 6.7, 7.0, 90.0)};
  Rng rng(1, 1);
  TransportParams one;
  one.transport_leader_weight = 1;
  EXPECT_NEAR(CarryStep(s.in, Quiet(), one, s.carry, rng, kTick).desired_heading.degrees(), 90.0,
              1e-9);
  TransportParams three;
  three.transport_leader_weight = 3;
  const MoveDecision d = CarryStep(s.in, Quiet(), three, s.carry, rng, kTick);
  EXPECT_NEAR(d.desired_heading.degrees(), std::atan2(1.0, -2.0) * 180.0 / M_PI, 1e-9);
  // The default, 4: (-3, 1) -> 161.6 degrees.
  EXPECT_EQ(TransportParams().transport_leader_weight, 4);
  EXPECT_NEAR(
      CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick).desired_heading.degrees(),
      std::atan2(1.0, -3.0) * 180.0 / M_PI, 1e-9);
  EXPECT_EQ(d.neighbours_in_range, 3);
  TransportParams bad;
  bad.transport_leader_weight = 0;
  EXPECT_EQ(bad.Validate(), "transport_leader_weight must be in [1, 255] but is 0");
}

TEST(CarryStepTest, ArrivedRobotsStand) {
  Scene s = Carrying(3.2, 3.0, 0.0, {3.02, 3.03}, false);
  Rng rng(1, 1);
  EXPECT_EQ(CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick).outcome,
            MoveOutcome::kStand);
}

TEST(CarryStepTest, FormationRobotsHoldTheirOffsetsAndMoveAsOneBody) {
  // Three robots in a tight row across the course, one just behind another along it: each
  // moves exactly the body's step, so the row keeps its shape (and no robot is in another's way).
  const Vec2 centre{7.0, 7.0};
  const std::vector<Vec2> places = {{7.0, 7.0}, {7.08, 7.08}, {6.9, 7.2}};
  TransportParams tp;
  const double step = 0.1 * tp.formation_speed_fraction;
  for (std::size_t i = 0; i < places.size(); ++i) {
    Scene s = Carrying(places[i].x, places[i].y, 45.0, centre, i == 0);
    s.in.self_id = static_cast<std::uint16_t>(i + 1);
    s.carry.mode = TransportMode::kFormation;
    s.carry.formation_offset = places[i] - centre;
    s.carry.peers.clear();
    for (std::size_t j = 0; j < places.size(); ++j) {
      if (j == i) continue;
      s.in.others.push_back(At(static_cast<std::uint16_t>(j + 1), places[j].x, places[j].y));
      s.carry.peers.push_back(static_cast<std::uint16_t>(j + 1));
    }
    Rng rng(1, 1);
    const MoveDecision d = CarryStep(s.in, Quiet(), tp, s.carry, rng, kTick);
    const Vec2 moved = Destination(s.in, d) - places[i];
    EXPECT_NEAR(moved.x, -step / std::sqrt(2.0), 1e-9) << i;
    EXPECT_NEAR(moved.y, -step / std::sqrt(2.0), 1e-9) << i;
  }
}

TEST(CarryStepTest, FormationRobotsPushedApartDoNotFightThePush) {
  // Two members anchored 0.1 apart (under the 0.11 separation) and pushed 5 mm off their
  // places by the simulator: each moves exactly the body's step, not back into the other.
  Scene s = Carrying(7.005, 7.0, 0.0, {7.0, 7.0}, false);
  s.carry.mode = TransportMode::kFormation;
  s.carry.formation_offset = {0.0, 0.0};
  s.carry.peers = {2};
  s.in.others = {At(2, 7.1, 7.0)};
  Rng rng(1, 1);
  TransportParams tp;
  const MoveDecision d = CarryStep(s.in, Quiet(), tp, s.carry, rng, kTick);
  const Vec2 moved = Destination(s.in, d) - s.in.self.position;
  const double step = 0.1 * tp.formation_speed_fraction / std::sqrt(2.0);
  EXPECT_NEAR(moved.x, -step, 1e-9);
  EXPECT_NEAR(moved.y, -step, 1e-9);
}

TEST(CarryStepTest, AFormationRobotOutOfPlaceRejoinsAtFullSpeed) {
  Scene s = Carrying(7.5, 7.0, 0.0, {7.0, 7.0}, false);
  s.carry.mode = TransportMode::kFormation;
  s.carry.formation_offset = {0.0, 0.5};  // its place is 0.5 m north-west of where it is
  Rng rng(1, 1);
  const MoveDecision d = CarryStep(s.in, Quiet(), TransportParams(), s.carry, rng, kTick);
  EXPECT_DOUBLE_EQ(d.distance_m, 0.1);
  const Vec2 to = Destination(s.in, d);
  EXPECT_LT(Distance(to, Vec2{7.0, 7.5}), Distance(s.in.self.position, Vec2{7.0, 7.5}) - 0.09);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
