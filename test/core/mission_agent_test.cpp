// The robot side of missions: zones, roles, FIFO, and the first leader's phase machine.
#include "swarm_transport/core/mission_agent.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "fixtures.h"
#include "mission_agent_fixture.h"

namespace swarm_transport {
namespace core {
namespace {

using fixtures::At;
using fixtures::Phases;
using fixtures::PoseAt;
using fixtures::Thesis;

TEST(MissionAgentTest, ObjectIsSafetyForItsRobotsAndDangerForOthers) {
  MissionAgent member(1, MissionAgentParams());
  MissionAgent other(5, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(member.OnNewMission(Thesis(), &why)) << why;
  ASSERT_TRUE(other.OnNewMission(Thesis(), &why)) << why;
  MissionOutbox out;
  const MissionPlan m = member.Tick(PoseAt(1.0, 1.0), {}, 0, &out);
  // Its own object is no zone to it: CarryStep binds it (a robot outside drives in).
  EXPECT_TRUE(m.zones.empty());
  ASSERT_TRUE(m.carry.has_value());
  EXPECT_FALSE(m.carry->object.Contains({1.0, 1.0}));  // outside its object: it must get in
  EXPECT_TRUE(m.carry->object.Contains({7.0, 7.0}));
  EXPECT_FALSE(m.lead);
  EXPECT_TRUE(out.empty());  // not the first leader: it sends nothing
  const MissionPlan o = other.Tick(PoseAt(1.0, 1.0), {}, 0, &out);
  ASSERT_EQ(o.zones.size(), 1u);
  EXPECT_FALSE(o.zones[0].inverted);
  EXPECT_TRUE(o.zones[0].Forbids({7.0, 7.0}));
  EXPECT_FALSE(o.active.has_value());
}

TEST(MissionAgentTest, FirstLeaderRunsTheWholeMission) {
  MissionAgent leader(0, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(leader.OnNewMission(Thesis(), &why));
  MissionOutbox out;
  // Robot 2 is still outside: gathering.
  leader.Tick(PoseAt(7.0, 7.0), {At(1, 7.5, 7.5), At(2, 1.0, 1.0)}, 1, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"GATHERING"});
  EXPECT_TRUE(out.freeze.empty());
  // Every assigned robot inside: freeze [0, 3), LOADING.
  out = MissionOutbox();
  leader.Tick(PoseAt(7.0, 7.0), {At(1, 7.5, 7.5), At(2, 6.5, 6.5)}, 2, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"LOADING"});
  ASSERT_EQ(out.freeze.size(), 1u);
  EXPECT_EQ(out.freeze[0], std::make_pair(std::uint16_t{0}, std::uint16_t{3}));
  // LOADED to take effect at tick 10: nothing before.
  ASSERT_TRUE(leader.OnEvent(7, MissionEventKind::kLoaded, 10, &why)) << why;
  out = MissionOutbox();
  leader.Tick(PoseAt(7.0, 7.0), {At(1, 7.5, 7.5), At(2, 6.5, 6.5)}, 9, &out);
  EXPECT_TRUE(out.empty());
  out = MissionOutbox();
  leader.Tick(PoseAt(7.0, 7.0), {At(1, 7.5, 7.5), At(2, 6.5, 6.5)}, 10, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"TRANSPORT"});
  EXPECT_EQ(out.resume.size(), 1u);
  // The centroid (7, 7) stays the object's centre offset (0, 0); the leader steers from the
  // object's centre to the target.
  out = MissionOutbox();
  MissionPlan plan = leader.Tick(PoseAt(5.0, 5.0), {At(1, 5.5, 5.5), At(2, 4.5, 4.5)}, 11, &out);
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_TRUE(plan.carry->leader);
  EXPECT_NEAR(Bearing(plan.carry->centre, plan.carry->target).degrees(), 225.0, 1e-9);
  ASSERT_TRUE(out.update_object.has_value());
  EXPECT_NEAR(out.update_object->second.x, 5.0, 1e-12);
  // Arrival within 0.05: last update, freeze, UNLOADING.
  out = MissionOutbox();
  leader.Tick(PoseAt(3.02, 3.0), {At(1, 3.52, 3.5), At(2, 2.52, 2.5)}, 12, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"UNLOADING"});
  EXPECT_EQ(out.freeze.size(), 1u);
  EXPECT_TRUE(out.update_object.has_value());
  // UNLOADED: continue, delete, DONE.
  ASSERT_TRUE(leader.OnEvent(7, MissionEventKind::kUnloaded, 0, &why));
  out = MissionOutbox();
  leader.Tick(PoseAt(3.02, 3.0), {At(1, 3.52, 3.5), At(2, 2.52, 2.5)}, 13, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"DONE"});
  EXPECT_EQ(out.resume.size(), 1u);
  EXPECT_EQ(out.delete_object, std::optional<std::uint16_t>(7));
  ASSERT_TRUE(leader.OnObjectDelete(7, &why));
  EXPECT_TRUE(leader.LiveIds().empty());
}

// Brings a fresh first leader of the thesis mission (robots [0, 3)) into TRANSPORT at tick 10,
// the centroid (7, 7) being the object's centre.
void IntoTransport(MissionAgent* leader) {
  std::string why;
  ASSERT_TRUE(leader->OnNewMission(Thesis(), &why));
  MissionOutbox out;
  leader->Tick(PoseAt(7.0, 7.0), {At(1, 7.5, 7.5), At(2, 6.5, 6.5)}, 1, &out);
  ASSERT_TRUE(leader->OnEvent(7, MissionEventKind::kLoaded, 10, &why)) << why;
  out = MissionOutbox();
  leader->Tick(PoseAt(7.0, 7.0), {At(1, 7.5, 7.5), At(2, 6.5, 6.5)}, 10, &out);
  ASSERT_EQ(Phases(out), std::vector<std::string>{"TRANSPORT"});
}

TEST(MissionAgentTest, ABalloonLoadingFreezesAfterTheSpreadAndTransportsOnlyAfterTheFreeze) {
  MissionAgentParams params;
  params.loading_spread = LoadingSpread::kBalloon;
  params.loading_spread_ticks = 5;
  MissionAgent leader(0, params);
  std::string why;
  ASSERT_TRUE(leader.OnNewMission(Thesis(), &why));
  const std::vector<Neighbour> inside{At(1, 7.5, 7.5), At(2, 6.5, 6.5)};
  MissionOutbox out;
  leader.Tick(PoseAt(7.0, 7.0), {At(1, 7.5, 7.5), At(2, 1.0, 1.0)}, 1, &out);
  // Everyone inside at tick 2: LOADING, but no freeze yet - the robots spread first.
  out = MissionOutbox();
  MissionPlan plan = leader.Tick(PoseAt(7.0, 7.0), inside, 2, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"LOADING"});
  EXPECT_TRUE(out.freeze.empty());
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_TRUE(plan.carry->loading);
  // LOADED takes effect at tick 3 already: the spread still holds the transport back.
  ASSERT_TRUE(leader.OnEvent(7, MissionEventKind::kLoaded, 3, &why)) << why;
  for (std::uint64_t tick = 3; tick < 7; ++tick) {
    out = MissionOutbox();
    leader.Tick(PoseAt(7.0, 7.0), inside, tick, &out);
    EXPECT_TRUE(out.freeze.empty()) << tick;
    EXPECT_TRUE(Phases(out).empty()) << tick;
  }
  // Tick 2 + 5: the freeze goes out; the transport starts at the tick after it.
  out = MissionOutbox();
  leader.Tick(PoseAt(7.0, 7.0), inside, 7, &out);
  ASSERT_EQ(out.freeze.size(), 1u);
  EXPECT_EQ(out.freeze[0], std::make_pair(std::uint16_t{0}, std::uint16_t{3}));
  EXPECT_TRUE(Phases(out).empty());
  out = MissionOutbox();
  leader.Tick(PoseAt(7.0, 7.0), inside, 8, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"TRANSPORT"});
  EXPECT_EQ(out.resume.size(), 1u);
  EXPECT_TRUE(out.freeze.empty());
}

TEST(MissionAgentTest, TheObjectMovesWithTheCurrentCentroidOfItsRobots) {
  MissionAgent leader(0, MissionAgentParams());
  IntoTransport(&leader);
  MissionOutbox out;
  // The robots moved by (-1, -1): so did the object (offset 0 from the centroid (7, 7)), this
  // tick, not one tick late.
  const MissionPlan plan =
      leader.Tick(PoseAt(6.0, 6.0), {At(1, 6.5, 6.5), At(2, 5.5, 5.5)}, 11, &out);
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_TRUE(plan.carry->transport);
  EXPECT_TRUE(plan.carry->leader);
  EXPECT_NEAR(plan.carry->centre.x, 6.0, 1e-9);
  EXPECT_NEAR(plan.carry->centre.y, 6.0, 1e-9);
  ASSERT_TRUE(out.update_object.has_value());
  EXPECT_NEAR(out.update_object->second.x, 6.0, 1e-9);
  // The object it is bound to (CarryStep) is where the robots are now.
  EXPECT_FALSE(plan.carry->object.Contains({7.5, 7.5}));
  EXPECT_TRUE(plan.carry->object.Contains({5.5, 5.5}));
}

TEST(MissionAgentTest, TheArenaWallHoldsTheObjectAndItsRobotsLeaveItBehind) {
  MissionAgent leader(0, MissionAgentParams());  // the thesis's 11.09 m arena
  IntoTransport(&leader);                        // a 2 x 2 object on the centroid (7, 7)
  MissionOutbox out;
  // The robots drove east to the wall (centroid (10.9, 7)): the object would stick out 0.8 m
  // beyond it. The wall holds it: its east edge on the wall, the robots still inside it.
  MissionPlan plan =
      leader.Tick(PoseAt(10.9, 7.0), {At(1, 10.95, 7.3), At(2, 10.85, 6.7)}, 11, &out);
  ASSERT_TRUE(plan.carry.has_value());
  const double wall = MissionAgentParams().world_size_m;
  EXPECT_NEAR(plan.carry->centre.x, wall - 1.0, 1e-9);
  EXPECT_NEAR(plan.carry->centre.y, 7.0, 1e-9);
  EXPECT_TRUE(plan.carry->object.Contains({10.9, 7.0}));
  ASSERT_TRUE(out.update_object.has_value());
  EXPECT_LE(out.update_object->second.x + 1.0, wall);  // an update every robot accepts
  // They turn back west by 1 m: the object goes with them from where the wall left it (it
  // slipped 0.81 m), not 0.81 m east of them again.
  out = MissionOutbox();
  plan = leader.Tick(PoseAt(9.9, 7.0), {At(1, 9.95, 7.3), At(2, 9.85, 6.7)}, 12, &out);
  EXPECT_NEAR(plan.carry->centre.x, wall - 2.0, 1e-9);
  EXPECT_TRUE(plan.carry->object.Contains({9.9, 7.0}));
}

TEST(MissionAgentTest, InsideArenaKeepsAnObjectInTheArena) {
  EXPECT_NEAR(InsideArena({11.37, 9.94}, {1.0, 1.0}, 11.0).x, 10.5, 1e-12);
  EXPECT_NEAR(InsideArena({11.37, 9.94}, {1.0, 1.0}, 11.0).y, 9.94, 1e-12);
  EXPECT_NEAR(InsideArena({-0.2, 0.1}, {1.0, 2.0}, 11.0).x, 0.5, 1e-12);
  EXPECT_NEAR(InsideArena({-0.2, 0.1}, {1.0, 2.0}, 11.0).y, 1.0, 1e-12);
  EXPECT_NEAR(InsideArena({3.0, 4.0}, {12.0, 1.0}, 11.0).x, 3.0, 1e-12);  // wider than the arena
  EXPECT_NEAR(InsideArena({12.0, 4.0}, {1.0, 1.0}, 0.0).x, 12.0, 1e-12);  // no arena
}

TEST(MissionAgentTest, EveryMemberAnchorsTheObjectToTheSameCentroid) {
  // A passive member learns TRANSPORT one tick after the first leader (the status is relayed);
  // everyone stood meanwhile, so it anchors the object where the first leader did.
  MissionAgent passive(1, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(passive.OnNewMission(Thesis(), &why));
  const std::vector<Neighbour> others = {At(0, 7.0, 7.4), At(2, 6.2, 6.9)};
  MissionPlan plan = passive.Tick(PoseAt(7.3, 7.2), others, 10, nullptr);
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_FALSE(plan.carry->transport);  // gathering / loading: the object stays put
  passive.OnStatus(7, MissionPhase::kTransport);
  plan = passive.Tick(PoseAt(7.3, 7.2), others, 11, nullptr);
  EXPECT_TRUE(plan.carry->transport);
  EXPECT_NEAR(plan.carry->centre.x, 7.0, 1e-9);
  EXPECT_NEAR(plan.carry->centre.y, 7.0, 1e-9);
  EXPECT_NEAR(plan.carry->formation_offset.x, 0.3, 1e-9);  // its place in a formation
  EXPECT_NEAR(plan.carry->formation_offset.y, 0.2, 1e-9);
  // All move by (-0.1, 0): so does the object.
  plan = passive.Tick(PoseAt(7.2, 7.2), {At(0, 6.9, 7.4), At(2, 6.1, 6.9)}, 12, nullptr);
  EXPECT_NEAR(plan.carry->centre.x, 6.9, 1e-9);
  EXPECT_NEAR(plan.carry->centre.y, 7.0, 1e-9);
}

TEST(MissionAgentTest, AMemberWhoseObjectDriftedTakesTheFirstLeaders) {
  // A passive member anchored late: the robots had moved off by (-0.4, 0) when its TRANSPORT
  // came (real time under load), so its object is 0.4 m east of the first leader's.
  MissionAgent passive(1, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(passive.OnNewMission(Thesis(), &why));
  passive.OnStatus(7, MissionPhase::kTransport);
  MissionPlan plan = passive.Tick(PoseAt(6.9, 7.2), {At(0, 6.6, 7.4), At(2, 5.8, 6.9)}, 11,
                                  nullptr);  // centroid (6.433, 7.167): object there + (0.567,
                                             // -0.167), i.e. (7, 7)
  ASSERT_TRUE(plan.carry.has_value() && plan.carry->transport);
  EXPECT_NEAR(plan.carry->centre.x, 7.0, 1e-9);
  // The first leader's update of that tick: its object is at (6.6, 7.0).
  ASSERT_TRUE(passive.OnObjectUpdate(7, {6.6, 7.0}, &why)) << why;
  // All move by (-0.1, 0): its object is the first leader's, moved with them.
  plan = passive.Tick(PoseAt(6.8, 7.2), {At(0, 6.5, 7.4), At(2, 5.7, 6.9)}, 12, nullptr);
  EXPECT_NEAR(plan.carry->centre.x, 6.5, 1e-9);
  EXPECT_NEAR(plan.carry->centre.y, 7.0, 1e-9);
  // Without an update it keeps that offset; an update that agrees changes nothing.
  plan = passive.Tick(PoseAt(6.7, 7.2), {At(0, 6.4, 7.4), At(2, 5.6, 6.9)}, 13, nullptr);
  EXPECT_NEAR(plan.carry->centre.x, 6.4, 1e-9);
  ASSERT_TRUE(passive.OnObjectUpdate(7, {6.4, 7.0}, &why)) << why;
  plan = passive.Tick(PoseAt(6.7, 7.2), {At(0, 6.4, 7.4), At(2, 5.6, 6.9)}, 14, nullptr);
  EXPECT_NEAR(plan.carry->centre.x, 6.4, 1e-9);
  EXPECT_NEAR(plan.carry->centre.y, 7.0, 1e-9);
}

TEST(MissionAgentTest, GatheringEndsWhenEveryoneIsInsideAndTheGroupIsOneChain) {
  // All three inside, but robot 2 stopped at the rim 1.34 from the others (local range 1.0):
  // starting now would leave it out of its group's reach, so gathering goes on.
  MissionAgent leader(0, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(leader.OnNewMission(Thesis(), &why));
  MissionOutbox out;
  leader.Tick(PoseAt(7.0, 7.0), {At(1, 7.5, 7.5), At(2, 6.05, 6.05)}, 1, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"GATHERING"});
  EXPECT_TRUE(out.freeze.empty());
  // It closed up: one chain, LOADING; the plan says so (a leader then faces its course).
  out = MissionOutbox();
  const MissionPlan plan =
      leader.Tick(PoseAt(7.0, 7.0), {At(1, 7.5, 7.5), At(2, 6.3, 6.3)}, 2, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"LOADING"});
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_TRUE(plan.carry->loading);
  // The evaluated code's rule: everyone inside is enough.
  MissionAgentParams thesis;
  thesis.transport.gather_one_chain = false;
  MissionAgent old(0, thesis);
  ASSERT_TRUE(old.OnNewMission(Thesis(), &why));
  out = MissionOutbox();
  old.Tick(PoseAt(7.0, 7.0), {At(1, 7.5, 7.5), At(2, 6.05, 6.05)}, 1, &out);
  EXPECT_EQ(Phases(out), (std::vector<std::string>{"GATHERING", "LOADING"}));
}

TEST(MissionAgentTest, PlannedGatheringGivesEveryMemberItsOwnSlotAndReplans) {
  // Three robots west of the object (7, 7) in a row; each computes the same plan from what it
  // hears, so the three slots differ, and every slot lies under the object.
  MissionAgentParams params;
  params.transport.gather_planner = GatherPlanner::kSelectionMatrix;
  params.transport.replan_period_ticks = 5;
  const std::vector<Vec2> where{{4.0, 7.0}, {4.0, 7.5}, {4.0, 6.5}};
  std::set<std::pair<double, double>> slots;
  for (std::uint16_t id = 0; id < 3; ++id) {
    MissionAgent agent(id, params);
    std::string why;
    ASSERT_TRUE(agent.OnNewMission(Thesis(), &why)) << why;
    std::vector<Neighbour> heard;
    for (std::uint16_t other = 0; other < 3; ++other) {
      if (other != id) heard.push_back(At(other, where[other].x, where[other].y));
    }
    MissionOutbox out;
    const MissionPlan plan = agent.Tick(Pose2{where[id], Angle(0.0)}, heard, 1, &out);
    ASSERT_TRUE(plan.carry && plan.carry->slot) << "robot " << id;
    EXPECT_TRUE(plan.carry->object.Contains(*plan.carry->slot));
    slots.insert({plan.carry->slot->x, plan.carry->slot->y});
    // Between re-plans the slot stays; at a multiple of replan_period it is planned anew on
    // the positions heard then (robot 0 alone near the east rim takes an east slot).
    const Vec2 first = *plan.carry->slot;
    const MissionPlan same = agent.Tick(Pose2{{7.9, 7.0}, Angle(0.0)}, {}, 2, &out);
    EXPECT_DOUBLE_EQ(same.carry->slot->x, first.x);
    if (id == 0) {
      const MissionPlan again = agent.Tick(Pose2{{7.9, 7.0}, Angle(0.0)}, heard, 5, &out);
      EXPECT_GT(again.carry->slot->x, 7.0);
    }
  }
  EXPECT_EQ(slots.size(), 3u);
}

TEST(MissionAgentTest, NearestGatheringHasNoSlot) {
  MissionAgent agent(1, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(agent.OnNewMission(Thesis(), &why)) << why;
  MissionOutbox out;
  const MissionPlan plan = agent.Tick(PoseAt(1.0, 1.0), {}, 0, &out);
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_FALSE(plan.carry->slot.has_value());
}

TEST(MissionAgentTest, TheObjectCanJumpOntoTheCentroidAtTransportStart) {
  // The robots' centroid is (7.2, 7.1) when transport starts: by default the object keeps its
  // centre (7, 7) and moves with the centroid; with object_at_centroid it is the centroid.
  for (const bool at_centroid : {false, true}) {
    MissionAgentParams params;
    params.transport.object_at_centroid = at_centroid;
    MissionAgent passive(1, params);
    std::string why;
    ASSERT_TRUE(passive.OnNewMission(Thesis(), &why));
    const std::vector<Neighbour> others = {At(0, 7.1, 7.5), At(2, 7.0, 6.8)};
    passive.Tick(PoseAt(7.5, 7.0), others, 10, nullptr);
    passive.OnStatus(7, MissionPhase::kTransport);
    const MissionPlan plan = passive.Tick(PoseAt(7.5, 7.0), others, 11, nullptr);
    ASSERT_TRUE(plan.carry.has_value());
    EXPECT_NEAR(plan.carry->centre.x, at_centroid ? 7.2 : 7.0, 1e-9) << at_centroid;
    EXPECT_NEAR(plan.carry->centre.y, at_centroid ? 7.1 : 7.0, 1e-9) << at_centroid;
    EXPECT_NEAR(plan.carry->formation_offset.x, at_centroid ? 0.3 : 0.5, 1e-9) << at_centroid;
  }
}

TEST(MissionAgentTest, FormationRobotsKnowTheirMode) {
  MissionAgent passive(1, MissionAgentParams());
  std::string why;
  MissionSpec spec = Thesis();
  spec.transport_mode = 1;
  ASSERT_TRUE(passive.OnNewMission(spec, &why));
  passive.OnStatus(7, MissionPhase::kTransport);
  const MissionPlan plan = passive.Tick(PoseAt(7.3, 7.2), {At(0, 7.0, 7.4)}, 11, nullptr);
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_EQ(plan.carry->mode, TransportMode::kFormation);
  EXPECT_EQ(plan.carry->peers, (std::vector<std::uint16_t>{0, 2}));
}

TEST(MissionAgentTest, ASwarmIsItsMissionGroupOrAllButOthersMissionGroups) {
  MissionAgent member(1, MissionAgentParams());
  MissionAgent idle(5, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(member.OnNewMission(Thesis(), &why));
  ASSERT_TRUE(idle.OnNewMission(Thesis(), &why));
  const MissionPlan m = member.Tick(PoseAt(1.0, 1.0), {}, 0, nullptr);
  EXPECT_TRUE(m.group.only);
  EXPECT_EQ(m.group.ids, (std::vector<std::uint16_t>{0, 1, 2}));
  const MissionPlan i = idle.Tick(PoseAt(1.0, 1.0), {}, 0, nullptr);
  EXPECT_FALSE(i.group.only);
  EXPECT_EQ(i.group.ids, (std::vector<std::uint16_t>{0, 1, 2}));
  EXPECT_FALSE(i.group.Admits(2));
  EXPECT_TRUE(i.group.Admits(4));
  // Once the object is deleted everyone is a candidate again.
  ASSERT_TRUE(idle.OnObjectDelete(7, &why));
  EXPECT_TRUE(idle.Tick(PoseAt(1.0, 1.0), {}, 1, nullptr).group.Admits(2));
}

TEST(MissionAgentTest, SignalsOutOfPhaseAreRejected) {
  MissionAgent leader(0, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(leader.OnNewMission(Thesis(), &why));
  EXPECT_FALSE(leader.OnEvent(7, MissionEventKind::kLoaded, 0, &why));
  EXPECT_NE(why.find("QUEUED"), std::string::npos) << why;  // no tick yet
  EXPECT_FALSE(leader.OnEvent(99, MissionEventKind::kLoaded, 0, &why));
}

TEST(MissionAgentTest, DuplicateLiveIdIsRejectedAndChangesNothing) {
  MissionAgent robot(1, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(robot.OnNewMission(Thesis(), &why));
  MissionSpec other = Thesis();
  other.object_centre = {2.0, 9.0};
  EXPECT_FALSE(robot.OnNewMission(other, &why));
  MissionOutbox out;
  const MissionPlan plan = robot.Tick(PoseAt(1.0, 1.0), {}, 0, &out);
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_TRUE(plan.carry->object.Contains({7.0, 7.0}));
  EXPECT_FALSE(plan.carry->object.Contains({2.0, 9.0}));
}

TEST(MissionAgentTest, MissionsQueueFirstInFirstOut) {
  MissionAgent robot(1, MissionAgentParams());
  std::string why;
  MissionSpec second = Thesis(8);
  second.object_centre = {2.0, 9.0};
  ASSERT_TRUE(robot.OnNewMission(Thesis(7), &why));
  ASSERT_TRUE(robot.OnNewMission(second, &why));
  MissionOutbox out;
  EXPECT_EQ(robot.Tick(PoseAt(1.0, 1.0), {}, 0, &out).active, std::optional<std::uint16_t>(7));
  ASSERT_TRUE(robot.OnObjectDelete(7, &why));
  EXPECT_EQ(robot.Tick(PoseAt(1.0, 1.0), {}, 1, &out).active, std::optional<std::uint16_t>(8));
}

TEST(MissionAgentTest, DispatcherStatusesDoNotMoveAMissionOn) {
  MissionAgent robot(1, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(robot.OnNewMission(Thesis(), &why));
  robot.OnStatus(7, MissionPhase::kTransport);
  robot.OnStatus(7, MissionPhase::kRejected);  // a refused duplicate of id 7
  EXPECT_EQ(robot.PhaseOf(7), MissionPhase::kTransport);
  robot.OnStatus(7, MissionPhase::kGathering);  // late: phases only move forward
  EXPECT_EQ(robot.PhaseOf(7), MissionPhase::kTransport);
}

TEST(MissionAgentTest, LeaderOnlyMissionLeadsThenEnds) {
  MissionSpec lead;
  lead.id = 21;
  lead.range_from = 4;
  lead.range_to = 5;
  lead.leader_number = 1;
  lead.target = {9.0, 9.0};
  MissionAgent robot(4, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(robot.OnNewMission(lead, &why));
  MissionOutbox out;
  const MissionPlan plan = robot.Tick(PoseAt(1.0, 1.0), {}, 0, &out);
  EXPECT_TRUE(plan.lead);
  EXPECT_TRUE(plan.keep_flock);
  EXPECT_TRUE(plan.zones.empty());
  EXPECT_NEAR(plan.steer.degrees(), 45.0, 1e-9);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"TRANSPORT"});
  out = MissionOutbox();
  robot.LeaderArrived(21, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"DONE"});
  EXPECT_EQ(out.delete_object, std::optional<std::uint16_t>(21));
  EXPECT_FALSE(robot.Tick(PoseAt(9.0, 9.0), {}, 1, &out).lead);
}

TEST(MissionAgentTest, AnObjectUpdateMustStayInTheArenaAndWithinReachOfItsRobots) {
  MissionAgentParams params;
  params.speed_m_per_tick = 0.1;
  MissionAgent agent(5, params);  // not in the mission: the object is a danger zone to it
  std::string why;
  agent.Tick(PoseAt(1.0, 1.0), {}, 10, nullptr);
  ASSERT_TRUE(agent.OnNewMission(Thesis(), &why)) << why;  // object at (7, 7) since tick 10
  // Outside the arena, or a jump no robot could carry it in one tick: refused, unchanged.
  EXPECT_FALSE(agent.OnObjectUpdate(7, {7.0, 20.0}, &why));
  EXPECT_NE(why.find("outside the arena"), std::string::npos) << why;
  EXPECT_FALSE(agent.OnObjectUpdate(7, {7.0, 9.0}, &why));
  EXPECT_NE(why.find("farther than its robots can carry it"), std::string::npos) << why;
  // One tick's drive: taken.
  EXPECT_TRUE(agent.OnObjectUpdate(7, {7.1, 7.0}, &why)) << why;
  agent.Tick(PoseAt(1.0, 1.0), {}, 11, nullptr);
  // After ten ticks without news it may have come ten ticks' worth farther.
  for (std::uint64_t t = 12; t < 21; ++t) agent.Tick(PoseAt(1.0, 1.0), {}, t, nullptr);
  EXPECT_TRUE(agent.OnObjectUpdate(7, {7.1, 8.9}, &why)) << why;
  EXPECT_NEAR(MaxObjectStep(1, 0.1), 0.4, 1e-12);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
