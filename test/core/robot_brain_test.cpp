// One robot's behaviour without ROS: its inbox (validation, freeze), one tick from perception
// to command, and the mission messages a first leader must send.
#include "swarm_transport/core/robot_brain.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "fixtures.h"

namespace swarm_transport {
namespace core {
namespace {

using fixtures::At;
using fixtures::Thesis;

SwarmConfig Params() {
  SwarmConfig p;
  p.flocking.local_range_m = 1.0;
  p.flocking.speed_m_per_tick = 0.1;
  p.flocking.free_will_deg = 90.0;
  p.tick_period_s = 1.0;
  p.seed = 3;
  return p;
}

Perception Sees(double x, double y, double heading_deg, std::vector<Neighbour> others) {
  Perception in;
  in.self = {{x, y}, Angle(heading_deg)};
  in.others = std::move(others);
  return in;
}

TEST(RobotBrainTest, FreezeHoldsTheRobotButNotItsBehaviour) {
  RobotBrain free(4, Params());
  RobotBrain held(4, Params());
  EXPECT_EQ(held.Take(Freeze{0, 4}), "");  // not its range
  EXPECT_FALSE(held.frozen());
  EXPECT_EQ(held.Take(Freeze{3, 5}), "");
  EXPECT_TRUE(held.frozen());
  const Perception in = Sees(5.0, 5.0, 30.0, {At(1, 5.5, 5.0, 90.0)});
  for (std::uint64_t tick = 0; tick < 3; ++tick) {
    const BrainTick a = free.Tick(in, tick, true);
    const BrainTick b = held.Tick(in, tick, true);
    // Same decision (its random sequence stays aligned), but it does not move.
    EXPECT_DOUBLE_EQ(a.move.heading.degrees(), b.move.heading.degrees());
    EXPECT_GT(a.command.linear, 0.0);
    EXPECT_EQ(b.command.linear, 0.0);
    EXPECT_EQ(b.command.angular, 0.0);
  }
  EXPECT_EQ(held.Take(Continue{4, 5}), "");
  EXPECT_FALSE(held.frozen());
  EXPECT_GT(held.Tick(in, 3, true).command.linear, 0.0);
}

TEST(RobotBrainTest, BalloonStandbyDrivesOffANeighbourUntilAMissionComes) {
  SwarmConfig config = Params();
  config.standby = StandbyMode::kBalloon;
  RobotBrain brain(2, config);
  RobotBrain flocking(2, Params());
  // A neighbour 0.3 m to the right: once the balloon passes 0.15 m it pushes the robot left.
  const Perception in = Sees(5.0, 5.0, 90.0, {At(1, 5.3, 5.0, 90.0)});
  BrainTick tick;
  for (std::uint64_t k = 0; k < 8; ++k) {
    tick = brain.Tick(in, k, true);
    flocking.Tick(in, k, true);
  }
  EXPECT_NEAR(brain.balloon_radius_m(), 0.05 + 8 * 0.02, 1e-9);
  EXPECT_NEAR(tick.move.heading.degrees(), 180.0, 1e-6);
  EXPECT_GT(tick.command.linear, 0.0);
  EXPECT_DOUBLE_EQ(flocking.balloon_radius_m(), 0.05);  // flock: no balloon
  // On a mission it leaves standby: the balloon is small again, the mission rules.
  MissionTaken taken;
  ASSERT_EQ(brain.Take(Thesis(), {0, 1, 2}, &taken), "");
  brain.Tick(in, 8, true);
  EXPECT_TRUE(brain.last_plan().active.has_value());
  EXPECT_DOUBLE_EQ(brain.balloon_radius_m(), 0.05);
}

TEST(RobotBrainTest, ABalloonLoadingMemberSpreadsUnderItsObjectUntilTheFreeze) {
  // Member 1 of the thesis mission, 0.2 m from member 2 inside the object, learns LOADING.
  SwarmConfig config = Params();
  config.loading_spread = LoadingSpread::kBalloon;
  RobotBrain spreading(1, config);
  RobotBrain standing(1, Params());
  MissionTaken taken;
  for (RobotBrain* brain : {&spreading, &standing}) {
    ASSERT_EQ(brain->Take(Thesis(), {0, 1, 2}, &taken), "");
    brain->Take(PhaseStatus{7, MissionPhase::kLoading, {}});
  }
  // none: the first leader froze the group at LOADING.
  ASSERT_EQ(standing.Take(Freeze{0, 3}), "");
  const Perception in = Sees(7.0, 7.0, 90.0, {At(0, 6.0, 6.5), At(2, 7.2, 7.0, 90.0)});
  BrainTick a, b;
  for (std::uint64_t k = 0; k < 8; ++k) {
    a = spreading.Tick(in, k, true);
    b = standing.Tick(in, k, true);
  }
  ASSERT_TRUE(spreading.last_plan().carry.has_value());
  EXPECT_TRUE(spreading.last_plan().carry->loading);
  // Its balloon passed 0.1 m (half the way to member 2): it drives off to the left.
  EXPECT_GT(spreading.balloon_radius_m(), 0.1);
  EXPECT_NEAR(a.move.heading.degrees(), 180.0, 1e-6);
  EXPECT_GT(a.command.linear, 0.0);
  EXPECT_EQ(b.command.linear, 0.0);  // none: frozen, nothing moves
  EXPECT_DOUBLE_EQ(standing.balloon_radius_m(), 0.05);
  // The first leader's freeze ends the spread: it stands.
  ASSERT_EQ(spreading.Take(Freeze{0, 3}), "");
  a = spreading.Tick(in, 8, true);
  EXPECT_EQ(a.command.linear, 0.0);
  EXPECT_DOUBLE_EQ(spreading.balloon_radius_m(), 0.05);
}

TEST(RobotBrainTest, AnEmptyOrInvertedRangeIsRejectedAndChangesNothing) {
  RobotBrain brain(4, Params());
  EXPECT_EQ(brain.Take(Freeze{5, 3}), "freeze [5, 3): the range is empty or inverted");
  EXPECT_EQ(brain.Take(Freeze{4, 4}), "freeze [4, 4): the range is empty or inverted");
  EXPECT_FALSE(brain.frozen());
  ASSERT_EQ(brain.Take(Freeze{4, 5}), "");
  EXPECT_NE(brain.Take(Continue{9, 0}), "");
  EXPECT_TRUE(brain.frozen());
}

TEST(RobotBrainTest, BadOrdersAreRejectedWithAReasonAndChangeNothing) {
  RobotBrain brain(0, Params());
  MissionSpec nan = Thesis();
  nan.target.x = std::nan("");
  MissionTaken taken;
  EXPECT_NE(brain.Take(nan, {}, &taken), "");
  MissionSpec unknown = Thesis();
  EXPECT_NE(brain.Take(unknown, {0, 1}, &taken), "");  // robot 2 does not exist
  EXPECT_TRUE(brain.missions().LiveIds().empty());
  ASSERT_EQ(brain.Take(Thesis(), {0, 1, 2}, &taken), "");
  EXPECT_TRUE(taken.first_leader);
  EXPECT_EQ(taken.queued.phase, MissionPhase::kQueued);
  EXPECT_EQ(taken.queued.assigned, 3);
  EXPECT_NEAR(taken.queued.distance_to_target, std::hypot(4.0, 4.0), 1e-12);
  MissionSpec again = Thesis();
  again.object_centre = {2.0, 9.0};
  EXPECT_NE(brain.Take(again, {}, &taken), "");  // a live id
  EXPECT_NE(brain.Take(ObjectUpdate{7, {std::nan(""), 1.0}}), "");
  EXPECT_NE(brain.Take(Signal{7, static_cast<MissionEventKind>(9), 0}), "");
  EXPECT_NE(brain.Take(ObjectDelete{99}), "");
  // The mission stands as ordered: robot 0 outside its object drives for the object at (7, 7).
  const BrainTick t = brain.Tick(Sees(5.0, 7.0, 0.0, {}), 0, true);
  EXPECT_NEAR(t.move.heading.degrees(), 0.0, 1e-9);
  // A passive robot takes it without being its first leader.
  RobotBrain passive(1, Params());
  ASSERT_EQ(passive.Take(Thesis(), {}, &taken), "");
  EXPECT_FALSE(taken.first_leader);
}

TEST(RobotBrainTest, AFirstLeaderRunsItsMissionAndAFrozenLeaderFacesItsCourse) {
  RobotBrain leader(0, Params());
  MissionTaken taken;
  ASSERT_EQ(leader.Take(Thesis(), {}, &taken), "");
  // Everyone inside and one chain: LOADING, freeze [0, 3).
  const std::vector<Neighbour> group = {At(1, 7.4, 7.0), At(2, 7.0, 7.4)};
  BrainTick t = leader.Tick(Sees(7.0, 7.0, 45.0, group), 1, true);
  ASSERT_EQ(t.outbox.statuses.size(), 2u);
  EXPECT_EQ(t.outbox.statuses[0].phase, MissionPhase::kGathering);
  EXPECT_EQ(t.outbox.statuses[1].phase, MissionPhase::kLoading);
  ASSERT_EQ(t.outbox.freeze.size(), 1u);
  ASSERT_EQ(leader.Take(Freeze{t.outbox.freeze[0].first, t.outbox.freeze[0].second}), "");
  // Frozen under its object it turns in place to its course (225 degrees) and does not drive.
  t = leader.Tick(Sees(7.0, 7.0, 45.0, group), 2, true);
  EXPECT_EQ(t.command.linear, 0.0);
  EXPECT_NEAR(std::fabs(t.command.angular), M_PI, 1e-9);  // 180 degrees in a 1 s tick
  // A first leader that cannot publish yet holds its phase machine and sends nothing.
  RobotBrain waiting(0, Params());
  ASSERT_EQ(waiting.Take(Thesis(), {}, &taken), "");
  EXPECT_TRUE(waiting.Tick(Sees(7.0, 7.0, 45.0, group), 1, false).outbox.empty());
  EXPECT_EQ(waiting.missions().PhaseOf(7), MissionPhase::kQueued);
}

TEST(RobotBrainTest, ALeaderOnlyMissionEndsWhenItsLeaderArrives) {
  SwarmConfig p = Params();
  p.leader.keep_flock = false;
  RobotBrain brain(4, p);
  MissionSpec lead;
  lead.id = 21;
  lead.range_from = 4;
  lead.range_to = 5;
  lead.leader_number = 1;
  lead.object_centre = {5.0, 4.9};
  lead.target = {5.0, 5.05};
  MissionTaken taken;
  ASSERT_EQ(brain.Take(lead, {}, &taken), "");
  BrainTick t = brain.Tick(Sees(5.0, 4.9, 0.0, {}), 0, true);
  EXPECT_FALSE(t.arrived);
  EXPECT_NEAR(t.move.heading.degrees(), 90.0, 1e-9);  // no free will: straight for the goal
  EXPECT_NEAR(t.command.linear, 0.1, 1e-12);
  t = brain.Tick(Sees(5.0, 5.0, 90.0, {}), 1, true);
  EXPECT_TRUE(t.arrived);
  ASSERT_FALSE(t.outbox.statuses.empty());
  EXPECT_EQ(t.outbox.statuses.back().phase, MissionPhase::kDone);
}

TEST(RobotBrainTest, TheSameSeedAndIdGiveTheSameRun) {
  RobotBrain a(2, Params());
  RobotBrain b(2, Params());
  RobotBrain other(3, Params());
  const Perception in = Sees(5.0, 5.0, 0.0, {});
  bool differs = false;
  for (std::uint64_t tick = 0; tick < 5; ++tick) {
    const BrainTick x = a.Tick(in, tick, true);
    const BrainTick y = b.Tick(in, tick, true);
    EXPECT_DOUBLE_EQ(x.command.angular, y.command.angular);
    differs = differs || other.Tick(in, tick, true).command.angular != x.command.angular;
  }
  EXPECT_TRUE(differs);  // each robot draws its own free will
}

TEST(RobotBrainTest, DeletingAMissionsObjectReleasesItsFrozenRobotsOnly) {
  RobotBrain member(1, Params());
  RobotBrain other(5, Params());
  for (RobotBrain* brain : {&member, &other}) {
    ASSERT_EQ(brain->Take(Thesis(), {}, nullptr), "");
    ASSERT_EQ(brain->Take(Freeze{0, 10}), "");
    ASSERT_TRUE(brain->frozen());
  }
  // A Delete_Object without the Robot_Continue before it (forged, or the leader lost).
  EXPECT_EQ(member.Take(ObjectDelete{7}), "");
  EXPECT_FALSE(member.frozen());
  EXPECT_EQ(other.Take(ObjectDelete{7}), "");
  EXPECT_TRUE(other.frozen());  // frozen by someone else's order: not the object's to release
  // An unknown mission's delete is rejected and releases nobody.
  ASSERT_EQ(member.Take(Freeze{0, 10}), "");
  EXPECT_NE(member.Take(ObjectDelete{99}), "");
  EXPECT_TRUE(member.frozen());
}

TEST(RobotBrainTest, AdmittingItselfARobotHoldsTheDispatchersLimit) {
  SwarmConfig p = Params();
  p.max_live_missions = 2;
  MissionSpec m = Thesis();
  // Under the dispatcher's admission the robot does not count: the dispatcher did.
  RobotBrain admitted(4, p);
  for (std::uint16_t id = 1; id <= 3; ++id) {
    m.id = id;
    EXPECT_EQ(admitted.Take(m, {}, nullptr), "") << id;
  }
  p.admission = Admission::kRobots;
  RobotBrain self(4, p);
  m.id = 1;
  EXPECT_EQ(self.Take(m, {}, nullptr), "");
  m.id = 2;
  EXPECT_EQ(self.Take(m, {}, nullptr), "");
  m.id = 3;
  const std::string why = self.Take(m, {}, nullptr);
  EXPECT_NE(why.find("too many live missions"), std::string::npos) << why;
  EXPECT_EQ(self.missions().Find(3), nullptr);
  EXPECT_NE(self.missions().Find(2), nullptr);
}

// Virtual leaders (SPEC 9.2), the hearer's side: the copies a robot announced with its position
// are neighbours of its hearers' flocking, whatever the hearer knows of missions or its own
// leader_virtual_copies.
TEST(RobotBrainTest, AHearerCountsTheCopiesALeaderAnnouncedAsNeighbours) {
  // Robot 4 hears robot 9 (heading 0) and two robots heading 90. No free will, no cohesion: the
  // desired heading is the alignment mean.
  SwarmConfig p = Params();
  p.flocking.free_will_deg = 0.0;
  p.flocking.cohesion = 0.0;
  p.flocking.neighbourhood = Neighbourhood::kDisc;
  double desired[2];
  for (const int copies : {0, 3}) {
    Neighbour leader = At(9, 5.5, 5.0, 0.0);
    leader.copies = static_cast<std::uint8_t>(copies);
    const Perception in =
        Sees(5.0, 5.0, 90.0, {leader, At(1, 4.5, 5.0, 90.0), At(2, 5.0, 5.5, 90.0)});
    RobotBrain brain(4, p);
    const BrainTick t = brain.Tick(in, 1, true);
    desired[copies == 0 ? 0 : 1] = t.move.desired_heading.degrees();
    EXPECT_EQ(t.move.neighbours_in_range, 4) << copies;  // itself and 3: copies are nobody
    EXPECT_EQ(t.copies, 0) << "a hearer announces nothing";
  }
  // The mean of unit headings: itself, 1 and 2 at 90 and 9 at 0 -> atan2(3, 1) = 71.6 deg;
  // with 3 copies of 9 -> atan2(3, 4) = 36.9 deg.
  EXPECT_NEAR(desired[0], 71.565, 0.01);
  EXPECT_NEAR(desired[1], 36.870, 0.01);
}

// In balloon standby a robot that hears a leader's copies flocks to follow it (as a robot of
// standby: flock does), and spreads out again when it hears none.
TEST(RobotBrainTest, ABalloonInStandbyFlocksWhileItHearsALeadersCopies) {
  SwarmConfig flock = Params();
  SwarmConfig balloon = flock;
  balloon.standby = StandbyMode::kBalloon;
  Neighbour leader = At(9, 5.4, 5.0, 0.0);
  leader.copies = 2;
  const Perception hears = Sees(5.0, 5.0, 90.0, {leader});
  RobotBrain flocking(4, flock);
  RobotBrain spreading(4, balloon);
  const BrainTick a = flocking.Tick(hears, 1, true);
  const BrainTick b = spreading.Tick(hears, 1, true);
  EXPECT_DOUBLE_EQ(a.move.desired_heading.degrees(), b.move.desired_heading.degrees());
  EXPECT_DOUBLE_EQ(a.command.angular, b.command.angular);
  leader.copies = 0;
  const Perception plain = Sees(5.0, 5.0, 90.0, {leader});
  const BrainTick c = flocking.Tick(plain, 2, true);
  const BrainTick d = spreading.Tick(plain, 2, true);
  EXPECT_NE(c.move.desired_heading.degrees(), d.move.desired_heading.degrees());
}

// The leader's side: it announces leader_virtual_copies - 1 copies while it leads a leader-only
// mission (not before, not after its arrival); a robot that does not lead announces none.
TEST(RobotBrainTest, ALeaderAnnouncesItsCopiesWhileItLeadsAlone) {
  MissionSpec trip;
  trip.id = 3;
  trip.range_from = 9;
  trip.range_to = 10;
  trip.leader_number = 1;
  trip.target = {9.0, 5.0};
  trip.object_centre = trip.target;
  for (const int k : {1, 4}) {
    SwarmConfig p = Params();
    p.leader.virtual_copies = k;
    RobotBrain leader(9, p);
    RobotBrain bystander(4, p);
    EXPECT_EQ(leader.Tick(Sees(5.0, 5.0, 0.0, {}), 0, true).copies, 0) << "no mission yet";
    for (RobotBrain* brain : {&leader, &bystander}) {
      ASSERT_EQ(brain->Take(trip, {}, nullptr), "");
      brain->Take(PhaseStatus{3, MissionPhase::kTransport, {}});
    }
    EXPECT_EQ(leader.Tick(Sees(5.0, 5.0, 0.0, {}), 1, true).copies, k - 1) << k;
    EXPECT_EQ(bystander.Tick(Sees(6.0, 6.0, 0.0, {}), 1, true).copies, 0) << k;
    // At its target it arrives (still leading this tick), then leads no more.
    const BrainTick arrival = leader.Tick(Sees(9.0, 5.0, 0.0, {}), 2, true);
    EXPECT_TRUE(arrival.arrived);
    EXPECT_EQ(leader.Tick(Sees(9.0, 5.0, 0.0, {}), 3, true).copies, 0) << k;
  }
  LeaderParams bad;
  bad.virtual_copies = 0;
  EXPECT_NE(bad.Validate(), "");
}

// Live tuning (issue 13): a valid change is used from the next tick on; a bad one is refused
// with the key named and changes nothing.
TEST(RobotBrainTest, AFlockingTuningAppliesFromTheNextTickAndABadOneChangesNothing) {
  RobotBrain brain(4, Params());
  const Perception alone = Sees(5.0, 5.0, 30.0, {});
  // Free will 90: a lone robot's wish strays from its heading (seed 3, 20 draws).
  double strayed = 0.0;
  for (std::uint64_t tick = 0; tick < 20; ++tick) {
    const BrainTick t = brain.Tick(alone, tick, true);
    strayed =
        std::max(strayed, std::abs(Angle::SignedDifference(t.move.desired_heading, Angle(30.0))));
    EXPECT_NEAR(t.move.distance_m, 0.1, 1e-12);
  }
  EXPECT_GT(strayed, 10.0);

  FlockingTuning calm = brain.tuning();
  EXPECT_DOUBLE_EQ(calm.free_will_deg, 90.0);
  calm.free_will_deg = 0.0;
  calm.cohesion = 0.0;
  calm.speed_m_per_tick = 0.05;
  calm.local_range_m = 2.0;
  ASSERT_EQ(brain.OnTuning(calm), "");
  EXPECT_TRUE(brain.tuning() == calm);
  for (std::uint64_t tick = 20; tick < 40; ++tick) {
    const BrainTick t = brain.Tick(alone, tick, true);
    EXPECT_NEAR(t.move.desired_heading.degrees(), 30.0, 1e-9) << tick;
    EXPECT_NEAR(t.move.distance_m, 0.05, 1e-12) << tick;
  }

  struct Case {
    void (*spoil)(FlockingTuning*);
    std::string names;
  };
  const Case cases[] = {
      {[](FlockingTuning* t) { t->free_will_deg = 400.0; }, "free_will_deg must be in [0, 360]"},
      {[](FlockingTuning* t) { t->free_will_deg = -1.0; }, "free_will_deg"},
      {[](FlockingTuning* t) { t->cohesion = std::nan(""); }, "cohesion must be in [-1, 1]"},
      {[](FlockingTuning* t) { t->cohesion = 1.5; }, "cohesion"},
      {[](FlockingTuning* t) { t->local_range_m = 0.0; }, "local_range_m"},
      // Speed and range are checked together: a step must stay within the range.
      {[](FlockingTuning* t) { t->speed_m_per_tick = 2.5; }, "speed_m_per_tick"},
      {[](FlockingTuning* t) { t->local_range_m = 0.04; }, "speed_m_per_tick"},
  };
  for (const Case& c : cases) {
    FlockingTuning bad = calm;
    c.spoil(&bad);
    const std::string why = brain.OnTuning(bad);
    EXPECT_NE(why.find(c.names), std::string::npos) << "'" << why << "' should name " << c.names;
    EXPECT_TRUE(brain.tuning() == calm) << c.names;
  }
  EXPECT_NEAR(brain.Tick(alone, 40, true).move.desired_heading.degrees(), 30.0, 1e-9);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
