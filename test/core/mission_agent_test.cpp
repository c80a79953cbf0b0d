// The robot side of missions: zones, roles, FIFO, and the first leader's phase machine.
#include "swarm_transport/core/mission_agent.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "fixtures.h"

namespace swarm_transport {
namespace core {
namespace {

using fixtures::At;
using fixtures::Thesis;

Pose2 PoseAt(double x, double y) { return Pose2{{x, y}, Angle(0.0)}; }

std::vector<std::string> Phases(const MissionOutbox& out) {
  std::vector<std::string> names;
  for (const StatusReport& r : out.statuses) names.push_back(PhaseName(r.phase));
  return names;
}

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

StatusReport Report(std::uint16_t id, MissionPhase phase) {
  StatusReport r;
  r.mission_id = id;
  r.phase = phase;
  return r;
}

std::vector<std::string> Names(const std::vector<StatusReport>& reports) {
  std::vector<std::string> names;
  for (const StatusReport& r : reports) {
    names.push_back(std::to_string(r.mission_id) + ":" + PhaseName(r.phase));
  }
  return names;
}

TEST(StatusSequencerTest, QueuedFirstThenEachPhaseOnceRepeatsAreProgress) {
  StatusSequencer seq;
  seq.Queue(Report(3, MissionPhase::kQueued));
  // Not ready and nothing else to say: the QUEUED waits.
  std::vector<StatusReport> statuses, progress;
  seq.Sequence(false, &statuses, &progress);
  EXPECT_TRUE(statuses.empty());
  // A mission that ends in its first tick: the QUEUED goes out before it even when not ready.
  statuses = {Report(3, MissionPhase::kGathering)};
  seq.Sequence(false, &statuses, &progress);
  EXPECT_EQ(Names(statuses), (std::vector<std::string>{"3:QUEUED", "3:GATHERING"}));
  EXPECT_TRUE(progress.empty());
  // The same phase again is progress; a new phase is a report.
  statuses = {Report(3, MissionPhase::kGathering), Report(3, MissionPhase::kLoading)};
  seq.Sequence(true, &statuses, &progress);
  EXPECT_EQ(Names(statuses), (std::vector<std::string>{"3:LOADING"}));
  EXPECT_EQ(Names(progress), (std::vector<std::string>{"3:GATHERING"}));
  // DONE is the last word: a reused id reports its phases afresh.
  statuses = {Report(3, MissionPhase::kDone)};
  progress.clear();
  seq.Sequence(true, &statuses, &progress);
  EXPECT_EQ(Names(statuses), (std::vector<std::string>{"3:DONE"}));
  statuses = {Report(3, MissionPhase::kLoading)};
  seq.Sequence(true, &statuses, &progress);
  EXPECT_EQ(Names(statuses), (std::vector<std::string>{"3:LOADING"}));
  EXPECT_TRUE(progress.empty());
}

TEST(SignalTickTest, TheDelayRoundsUpToWholeTicks) {
  EXPECT_EQ(SignalTick(65, 2.0, 1.1), 67u);  // 1.82 ticks -> 2
  EXPECT_EQ(SignalTick(65, 2.2, 1.1), 67u);  // exactly 2 ticks (within float error)
  EXPECT_EQ(SignalTick(65, 0.0, 1.1), 65u);
  EXPECT_EQ(SignalTick(10, 2.0, 0.1), 30u);
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

TEST(MissionAgentTest, AFirstLeaderReportsInEveryRunningPhaseAsItsHeartbeat) {
  MissionAgentParams params;
  params.progress_every_ticks = 10;
  MissionAgent leader(0, params);
  std::string why;
  MissionSpec spec = Thesis();
  spec.range_to = 1;  // the leader alone: gathered as soon as it is inside
  ASSERT_TRUE(leader.OnNewMission(spec, &why)) << why;
  MissionOutbox out;
  std::uint64_t loading_tick = 0;
  for (std::uint64_t t = 1; t < 60 && loading_tick == 0; ++t) {
    out = MissionOutbox();
    leader.Tick(PoseAt(7.0, 7.0), {}, t, &out);
    for (const StatusReport& r : out.statuses) {
      if (r.phase == MissionPhase::kLoading) loading_tick = t;
    }
  }
  ASSERT_GT(loading_tick, 0u);
  // No LOADED comes (a user's signal, say): LOADING is reported every 10 ticks meanwhile.
  std::vector<std::uint64_t> reports;
  for (std::uint64_t t = loading_tick + 1; t <= loading_tick + 30; ++t) {
    out = MissionOutbox();
    leader.Tick(PoseAt(7.0, 7.0), {}, t, &out);
    for (const StatusReport& r : out.statuses) {
      if (r.phase == MissionPhase::kLoading) reports.push_back(t - loading_tick);
    }
  }
  EXPECT_EQ(reports, (std::vector<std::uint64_t>{10, 20, 30}));
}

TEST(MissionAgentTest, AFirstLeaderDropsAMemberSilentInGatheringOrAbortsWithoutEnough) {
  MissionAgentParams params;
  params.lost_after_ticks = 5;
  MissionSpec spec = Thesis();  // robots [0, 3), robot 0 the only leader, object at (7, 7)
  MissionAgent leader(0, params);
  std::string why;
  ASSERT_TRUE(leader.OnNewMission(spec, &why)) << why;
  // Robot 1 is inside and heard every tick; robot 2 is never heard (its radio is silent).
  const std::vector<Neighbour> heard = {At(1, 7.2, 7.0)};
  MissionOutbox out;
  std::vector<MissionPhase> phases;
  std::string reason;
  std::string notice;
  std::uint64_t notice_tick = 0;
  for (std::uint64_t t = 1; t <= 10; ++t) {
    out = MissionOutbox();
    leader.Tick(PoseAt(7.0, 7.0), heard, t, &out);
    for (const StatusReport& r : out.statuses) {
      phases.push_back(r.phase);
      if (r.phase == MissionPhase::kLoading) reason = r.reason;
      if (r.phase == MissionPhase::kGathering && !r.reason.empty()) {
        EXPECT_TRUE(notice.empty()) << "named twice: " << notice << " / " << r.reason;
        notice = r.reason;
        notice_tick = t;
      }
    }
  }
  // Gathered without it once it was silent for more than 5 ticks (from the first tick on): the
  // first leader names it at once (GATHERING again: a progress report), then loads.
  ASSERT_EQ(phases, (std::vector<MissionPhase>{MissionPhase::kGathering, MissionPhase::kGathering,
                                               MissionPhase::kLoading}));
  EXPECT_EQ(notice_tick, 7u);
  EXPECT_EQ(notice, "robot(s) 2 lost (not heard for 5 ticks): the mission goes on without them");
  EXPECT_NE(reason.find("without robot(s) 2 (lost"), std::string::npos) << reason;
  // The sequencer sends the repeat as progress, so the phase reports stay one per phase.
  StatusSequencer sequencer;
  std::vector<StatusReport> reports(2), progress;
  reports[0].mission_id = reports[1].mission_id = spec.id;
  reports[0].phase = reports[1].phase = MissionPhase::kGathering;
  reports[1].reason = notice;
  sequencer.Sequence(true, &reports, &progress);
  ASSERT_EQ(reports.size(), 1u);
  ASSERT_EQ(progress.size(), 1u);
  EXPECT_EQ(progress[0].reason, notice);

  // With 2 leaders and both others silent, fewer robots than leaders are left: ABORTED.
  spec.id = 8;
  spec.leader_number = 2;
  MissionAgent alone(0, params);
  ASSERT_TRUE(alone.OnNewMission(spec, &why)) << why;
  phases.clear();
  for (std::uint64_t t = 1; t <= 10; ++t) {
    out = MissionOutbox();
    alone.Tick(PoseAt(7.0, 7.0), {}, t, &out);
    for (const StatusReport& r : out.statuses) {
      phases.push_back(r.phase);
      if (r.phase == MissionPhase::kAborted) {
        reason = r.reason;
        EXPECT_EQ(out.delete_object, std::optional<std::uint16_t>(8));  // its object goes
      }
    }
  }
  ASSERT_EQ(phases, (std::vector<MissionPhase>{MissionPhase::kGathering, MissionPhase::kAborted}));
  EXPECT_NE(reason.find("robot(s) 1, 2 lost"), std::string::npos) << reason;
}

// Robot loss (issue 11, SPEC 9.7): a member that follows the thesis mission (robots [0, 3),
// robot 0 its only leader) through GATHERING, LOADING and into TRANSPORT at tick 10, every robot
// heard every tick, the group's centroid at the object's centre (7, 7).
void MemberIntoTransport(MissionAgent* member, MissionSpec spec = Thesis()) {
  std::string why;
  ASSERT_TRUE(member->OnNewMission(spec, &why)) << why;
  const Pose2 self = PoseAt(7.5, 7.5);
  const std::vector<Neighbour> heard = {At(0, 7.0, 7.0), At(2, 6.5, 6.5), At(3, 7.0, 7.5)};
  MissionOutbox out;
  member->OnStatus(spec.id, MissionPhase::kGathering);
  member->Tick(self, heard, 1, &out);
  member->OnStatus(spec.id, MissionPhase::kLoading);
  for (std::uint64_t t = 2; t <= 9; ++t) member->Tick(self, heard, t, &out);
  member->OnStatus(spec.id, MissionPhase::kTransport);
  member->Tick(self, heard, 10, &out);
  ASSERT_TRUE(out.empty());  // a member says nothing
}

TEST(MissionAgentTest, ALostFirstLeaderIsReplacedByTheNextAssignedRobot) {
  MissionAgentParams params;
  params.lost_after_ticks = 5;
  MissionAgent robot1(1, params);
  MemberIntoTransport(&robot1);
  EXPECT_FALSE(robot1.IsFirstLeaderOfAny());
  // Robot 0 (the first leader) falls silent after tick 10; robot 2 is still heard.
  MissionOutbox out;
  MissionPlan plan;
  std::uint64_t t = 11;
  for (; t <= 15; ++t) {
    plan = robot1.Tick(PoseAt(7.5, 7.5), {At(2, 6.5, 6.5)}, t, &out);
    ASSERT_FALSE(robot1.IsFirstLeaderOfAny()) << "promoted at tick " << t;
    ASSERT_TRUE(plan.carry.has_value());
    EXPECT_FALSE(plan.carry->leader);
    // Until it is lost, the silent robot counts where it was last heard: the object stays.
    EXPECT_NEAR(plan.carry->centre.x, 7.0, 1e-12);
  }
  EXPECT_TRUE(out.empty());
  // Tick 16: silent for more than 5 ticks, robot 0 is lost; robot 1 now leads (and carries
  // as a leader) and the object does not jump although the centroid of the robots left moved.
  plan = robot1.Tick(PoseAt(7.5, 7.5), {At(2, 6.5, 6.5)}, 16, &out);
  EXPECT_EQ(robot1.LostOf(7), (std::set<std::uint16_t>{0}));
  EXPECT_TRUE(robot1.IsFirstLeaderOfAny());
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_TRUE(plan.carry->leader);
  EXPECT_EQ(plan.carry->leaders, (std::vector<std::uint16_t>{1}));
  EXPECT_NEAR(plan.carry->centre.x, 7.0, 1e-12);
  EXPECT_NEAR(plan.carry->centre.y, 7.0, 1e-12);
  EXPECT_TRUE(out.empty());  // it takes over from the next tick on
  // Tick 17: it announces itself in the phase it took over, then runs the phase machine: the
  // object moves with the robots left from where it was.
  out = MissionOutbox();
  plan = robot1.Tick(PoseAt(7.4, 7.4), {At(2, 6.4, 6.4)}, 17, &out);
  ASSERT_EQ(Phases(out), std::vector<std::string>{"TRANSPORT"});
  EXPECT_NE(out.statuses[0].reason.find("robot 1 leads: robot(s) 0 lost"), std::string::npos)
      << out.statuses[0].reason;
  ASSERT_TRUE(out.update_object.has_value());
  EXPECT_NEAR(out.update_object->second.x, 6.9, 1e-12);
  EXPECT_NEAR(out.update_object->second.y, 6.9, 1e-12);
  // The robot that came back counts too late: it stays lost for the mission.
  out = MissionOutbox();
  robot1.Tick(PoseAt(7.4, 7.4), {At(0, 7.0, 7.0), At(2, 6.4, 6.4)}, 18, &out);
  EXPECT_TRUE(robot1.IsFirstLeaderOfAny());
  EXPECT_EQ(robot1.LostOf(7), (std::set<std::uint16_t>{0}));
}

TEST(MissionAgentTest, LostLeadersAreReplacedInOrderAndAFirstLeaderToBeKeepsTheSignals) {
  MissionAgentParams params;
  params.lost_after_ticks = 5;
  MissionSpec spec = Thesis();
  spec.range_to = 4;
  spec.leader_number = 2;  // leaders 0 and 1; robots 2 and 3 passive
  MissionAgent robot2(2, params);
  std::string why;
  ASSERT_TRUE(robot2.OnNewMission(spec, &why)) << why;
  const Pose2 self = PoseAt(6.5, 6.5);
  MissionOutbox out;
  robot2.OnStatus(7, MissionPhase::kGathering);
  robot2.Tick(self, {At(0, 7.0, 7.0), At(1, 7.5, 7.5), At(3, 7.0, 7.5)}, 1, &out);
  robot2.OnStatus(7, MissionPhase::kLoading);
  // The dispatcher's LOADED (to take effect at tick 12) reaches every member.
  ASSERT_TRUE(robot2.OnEvent(7, MissionEventKind::kLoaded, 12, &why)) << why;
  // Both leaders fall silent in LOADING.
  for (std::uint64_t t = 2; t <= 7; ++t) robot2.Tick(self, {At(3, 7.0, 7.5)}, t, &out);
  EXPECT_TRUE(out.empty());
  EXPECT_EQ(robot2.LostOf(7), (std::set<std::uint16_t>{0, 1}));
  EXPECT_TRUE(robot2.IsFirstLeaderOfAny());  // the lowest robot left
  out = MissionOutbox();
  MissionPlan plan = robot2.Tick(self, {At(3, 7.0, 7.5)}, 8, &out);
  ASSERT_EQ(Phases(out), std::vector<std::string>{"LOADING"});
  EXPECT_NE(out.statuses[0].reason.find("robot(s) 0, 1 lost"), std::string::npos);
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_EQ(plan.carry->leaders, (std::vector<std::uint16_t>{2, 3}));  // both promoted
  // The LOADED it kept as a member takes effect at its tick.
  out = MissionOutbox();
  robot2.Tick(self, {At(3, 7.0, 7.5)}, 11, &out);
  EXPECT_TRUE(Phases(out).empty());
  out = MissionOutbox();
  robot2.Tick(self, {At(3, 7.0, 7.5)}, 12, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"TRANSPORT"});
  EXPECT_EQ(out.resume.size(), 1u);
}

TEST(MissionAgentTest, NamedLeadersLeadAndALostOneIsReplacedByTheNextInLeadOrder) {
  MissionAgentParams params;
  params.lost_after_ticks = 5;
  MissionSpec spec = Thesis();
  spec.range_to = 4;
  spec.leader_number = 2;
  spec.leader_ids = {3, 2};  // named (a count-only mission's front robots): 0 and 1 passive
  MissionAgent robot0(0, params);
  MissionAgent robot3(3, params);
  std::string why;
  ASSERT_TRUE(robot0.OnNewMission(spec, &why)) << why;
  ASSERT_TRUE(robot3.OnNewMission(spec, &why)) << why;
  robot0.OnStatus(7, MissionPhase::kGathering);
  robot3.OnStatus(7, MissionPhase::kGathering);
  MissionOutbox out;
  MissionPlan plan =
      robot0.Tick(PoseAt(6.5, 6.5), {At(1, 7.5, 7.5), At(2, 7.0, 7.0), At(3, 7.0, 7.5)}, 1, &out);
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_EQ(plan.carry->leaders, (std::vector<std::uint16_t>{2, 3}));
  EXPECT_FALSE(plan.carry->leader);
  EXPECT_FALSE(robot0.IsFirstLeaderOfAny());  // robot 2 is: the lowest named leader
  EXPECT_FALSE(robot3.IsFirstLeaderOfAny());
  // Robot 2 falls silent: robot 3 leads first, robot 0 (the next in LeadOrder) leads too.
  for (std::uint64_t t = 2; t <= 8; ++t) {
    out = MissionOutbox();
    plan = robot0.Tick(PoseAt(6.5, 6.5), {At(1, 7.5, 7.5), At(3, 7.0, 7.5)}, t, &out);
    robot3.Tick(PoseAt(7.0, 7.5), {At(0, 6.5, 6.5), At(1, 7.5, 7.5)}, t, nullptr);
  }
  EXPECT_EQ(robot0.LostOf(7), (std::set<std::uint16_t>{2}));
  ASSERT_TRUE(plan.carry.has_value());
  EXPECT_EQ(plan.carry->leaders, (std::vector<std::uint16_t>{0, 3}));
  EXPECT_TRUE(plan.carry->leader);
  EXPECT_FALSE(robot0.IsFirstLeaderOfAny());
  EXPECT_TRUE(robot3.IsFirstLeaderOfAny());
}

TEST(MissionAgentTest, AFirstLeaderDropsAMemberLostInLoadingAndCarriesOn) {
  MissionAgentParams params;
  params.lost_after_ticks = 5;
  const MissionSpec spec = Thesis();  // robots [0, 3), robot 0 the only leader, object at (7, 7)
  MissionAgent leader(0, params);
  std::string why;
  ASSERT_TRUE(leader.OnNewMission(spec, &why)) << why;
  const Pose2 self = PoseAt(7.0, 7.0);
  const std::vector<Neighbour> both = {At(1, 7.2, 7.0), At(2, 6.8, 7.0)};
  MissionOutbox out;
  std::uint64_t t = 0;
  std::uint64_t loading = 0;
  while (loading == 0 && t < 10) {
    out = MissionOutbox();
    leader.Tick(self, both, ++t, &out);
    for (const StatusReport& r : out.statuses) {
      if (r.phase == MissionPhase::kLoading) loading = t;
    }
  }
  ASSERT_GT(loading, 0u) << "never loaded";
  ASSERT_TRUE(leader.OnEvent(7, MissionEventKind::kLoaded, loading + 20, &why)) << why;
  // Robot 2 falls silent in LOADING: named at once when lost, and the mission carries on.
  std::vector<std::pair<std::uint64_t, StatusReport>> reports;
  for (t = loading + 1; t <= loading + 20; ++t) {
    out = MissionOutbox();
    leader.Tick(self, {At(1, 7.2, 7.0)}, t, &out);
    for (const StatusReport& r : out.statuses) reports.emplace_back(t, r);
  }
  ASSERT_EQ(reports.size(), 2u);
  EXPECT_EQ(reports[0].first, loading + 6);  // silent for more than 5 ticks
  EXPECT_EQ(reports[0].second.phase, MissionPhase::kLoading);
  EXPECT_EQ(reports[0].second.reason,
            "robot(s) 2 lost (not heard for 5 ticks): the mission goes on without them");
  EXPECT_EQ(reports[1].first, loading + 20);  // the LOADED takes effect
  EXPECT_EQ(reports[1].second.phase, MissionPhase::kTransport);
  EXPECT_EQ(leader.LostOf(7), (std::set<std::uint16_t>{2}));
}

TEST(MissionAgentTest, AMissionWithFewerRobotsLeftThanLeadersEndsAborted) {
  MissionAgentParams params;
  params.lost_after_ticks = 5;
  MissionSpec spec = Thesis();
  spec.leader_number = 2;  // robots [0, 3): leaders 0 and 1
  MissionAgent robot1(1, params);
  MemberIntoTransport(&robot1, spec);
  // Robots 0 and 2 fall silent: one robot cannot staff two leaders.
  MissionOutbox out;
  for (std::uint64_t t = 11; t <= 16; ++t) robot1.Tick(PoseAt(7.5, 7.5), {}, t, &out);
  EXPECT_TRUE(robot1.IsFirstLeaderOfAny());
  out = MissionOutbox();
  robot1.Tick(PoseAt(7.5, 7.5), {}, 17, &out);
  ASSERT_EQ(Phases(out), (std::vector<std::string>{"TRANSPORT", "ABORTED"}));
  EXPECT_NE(out.statuses[1].reason.find("robot(s) 0, 2 lost"), std::string::npos)
      << out.statuses[1].reason;
  EXPECT_NE(out.statuses[1].reason.find("fewer robots than leaders"), std::string::npos);
  EXPECT_EQ(out.delete_object, std::optional<std::uint16_t>(7));
  EXPECT_EQ(out.resume.size(), 1u);  // everyone it froze is released
}

TEST(MissionAgentTest, AMissionBelowMinRobotsEndsAbortedNamingTheLost) {
  // Robots [0, 3), robot 0 leads; robot 1 is a member. Robot 0 falls silent: robot 1 is
  // promoted, and with mission_min_robots 3 the two left are too few.
  for (const int min_robots : {3, 0}) {
    MissionAgentParams params;
    params.lost_after_ticks = 5;
    params.min_robots = min_robots;
    MissionAgent robot1(1, params);
    MemberIntoTransport(&robot1);
    MissionOutbox out;
    std::vector<std::string> phases;
    for (std::uint64_t t = 11; t <= 18; ++t) {
      out = MissionOutbox();
      robot1.Tick(PoseAt(7.4, 7.4), {At(2, 6.4, 6.4)}, t, &out);
      for (const std::string& phase : Phases(out)) phases.push_back(phase);
      if (!out.statuses.empty() && Phases(out).back() == "ABORTED") {
        EXPECT_NE(out.statuses.back().reason.find("robot(s) 0 lost"), std::string::npos)
            << out.statuses.back().reason;
        EXPECT_NE(out.statuses.back().reason.find("2 robots left, fewer than mission_min_robots 3"),
                  std::string::npos)
            << out.statuses.back().reason;
      }
    }
    const bool aborted = std::find(phases.begin(), phases.end(), "ABORTED") != phases.end();
    EXPECT_EQ(aborted, min_robots == 3) << min_robots;  // the default only drops the robot
  }
}

TEST(MissionAgentTest, ARobotThatMissedItsTicksCountsItselfLostAndDoesNotLead) {
  MissionAgentParams params;
  params.lost_after_ticks = 5;
  MissionAgent robot0(0, params);
  std::string why;
  ASSERT_TRUE(robot0.OnNewMission(Thesis(), &why)) << why;
  MissionOutbox out;
  const std::vector<Neighbour> heard = {At(1, 7.5, 7.5), At(2, 1.0, 1.0)};
  robot0.Tick(PoseAt(7.0, 7.0), heard, 1, &out);
  ASSERT_EQ(Phases(out), std::vector<std::string>{"GATHERING"});
  // Hung from tick 2 to 9: the others lost it and robot 1 leads now.
  out = MissionOutbox();
  robot0.Tick(PoseAt(7.0, 7.0), heard, 10, &out);
  EXPECT_TRUE(out.empty());
  EXPECT_FALSE(robot0.IsFirstLeaderOfAny());
  EXPECT_EQ(robot0.LostOf(7), (std::set<std::uint16_t>{0}));
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
