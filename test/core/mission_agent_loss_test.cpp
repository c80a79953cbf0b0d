// Robot loss on the robot side of missions: heartbeats, dropped members, replaced leaders and
// aborted missions (issue 11, SPEC 9.7).
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <utility>
#include <vector>

#include "fixtures.h"
#include "mission_agent_fixture.h"
#include "swarm_transport/core/mission_agent.h"

namespace swarm_transport {
namespace core {
namespace {

using fixtures::At;
using fixtures::Phases;
using fixtures::PoseAt;
using fixtures::Thesis;

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

TEST(MissionAgentTest, AMemberLostInGatheringIsPlannedWithoutAtOnce) {
  // Robots [0, 4) gather by a plan replanned only every 100 ticks; robot 3 falls silent after
  // tick 1 and is lost at tick 7 (silent for more than 5 ticks): robot 1 replans at once over
  // the three left and their three slots (issue 27, item 7), for every planner that plans.
  for (const GatherPlanner planner : {GatherPlanner::kSelectionMatrix, GatherPlanner::kOptimal,
                                      GatherPlanner::kBottleneck, GatherPlanner::kRowMinimum}) {
    SCOPED_TRACE(GatherPlannerName(planner));
    MissionAgentParams params;
    params.lost_after_ticks = 5;
    params.transport.gather_planner = planner;
    params.transport.replan_period_ticks = 100;
    MissionSpec spec = Thesis();
    spec.range_to = 4;
    MissionAgent member(1, params);
    std::string why;
    ASSERT_TRUE(member.OnNewMission(spec, &why)) << why;
    const Pose2 self = PoseAt(3.0, 7.0);
    const std::vector<Neighbour> all = {At(0, 3.0, 6.0), At(2, 3.0, 8.0), At(3, 3.0, 9.0)};
    const std::vector<Neighbour> left(all.begin(), all.begin() + 2);
    MissionOutbox out;
    member.OnStatus(spec.id, MissionPhase::kGathering);
    member.Tick(self, all, 1, &out);
    ASSERT_TRUE(member.last_gather_plan());
    EXPECT_EQ(member.last_gather_plan()->ids, (std::vector<std::uint16_t>{0, 1, 2, 3}));
    MissionPlan plan;
    for (std::uint64_t t = 2; t <= 6; ++t) {
      member.Tick(self, left, t, &out);
      EXPECT_EQ(member.last_gather_plan()->tick, 1u) << "tick " << t;
    }
    plan = member.Tick(self, left, 7, &out);
    EXPECT_EQ(member.LostOf(spec.id), (std::set<std::uint16_t>{3}));
    const GatherPlanRecord& record = *member.last_gather_plan();
    EXPECT_EQ(record.tick, 7u);
    EXPECT_EQ(record.ids, (std::vector<std::uint16_t>{0, 1, 2}));
    ASSERT_EQ(record.plan.target_of.size(), 3u);
    for (int slot : record.plan.target_of) EXPECT_GE(slot, 0);  // SlotsIn gives 4 for 3 here
    ASSERT_TRUE(plan.carry && plan.carry->slot);
    const Vec2 own = record.targets[static_cast<std::size_t>(record.plan.target_of[1])].position;
    EXPECT_EQ(plan.carry->slot->x, own.x);
    EXPECT_EQ(plan.carry->slot->y, own.y);
    // And no other plan until the next period.
    member.Tick(self, left, 8, &out);
    EXPECT_EQ(member.last_gather_plan()->tick, 7u);
  }
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
  // Its status names the lost robot: the others (robot 0 itself too) learn it from there.
  EXPECT_EQ(out.statuses[0].lost, (std::vector<std::uint16_t>{0}));
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

  // In a real-time simulation its peers heard it all along (the simulator relays its pose): it
  // goes on leading after the same gap (issue 29: counting itself lost left the mission
  // without a first leader), until its first leader's status names it lost.
  params.heard_while_hung = true;
  MissionAgent starved(0, params);
  ASSERT_TRUE(starved.OnNewMission(Thesis(), &why)) << why;
  out = MissionOutbox();
  starved.Tick(PoseAt(7.0, 7.0), heard, 1, &out);
  ASSERT_EQ(Phases(out), std::vector<std::string>{"GATHERING"});
  out = MissionOutbox();
  starved.Tick(PoseAt(7.0, 7.0), heard, 10, &out);
  EXPECT_TRUE(starved.IsFirstLeaderOfAny());
  EXPECT_TRUE(starved.LostOf(7).empty());
  starved.OnStatus(7, MissionPhase::kGathering, {0});
  EXPECT_FALSE(starved.IsFirstLeaderOfAny());
}

TEST(MissionAgentTest, EveryRobotOfAMissionCountsLostWhomItsFirstLeaderCountsLost) {
  // A burst of radio loss (issue 29): robot 1 did not hear the first leader, robot 0, for long
  // enough and leads in its place, while robot 0 heard the others and went on leading - two
  // first leaders of one mission, which then stood in TRANSPORT for good. Robot 1's status
  // names robot 0 lost: robot 0 counts itself lost and stops leading, and a robot that had
  // counted robot 1 lost already is promoted by it.
  MissionAgentParams params;
  params.lost_after_ticks = 5;
  std::string why;
  MissionAgent robot0(0, params);
  ASSERT_TRUE(robot0.OnNewMission(Thesis(), &why)) << why;
  MissionOutbox out;
  const std::vector<Neighbour> heard = {At(1, 4.0, 4.0), At(2, 7.2, 7.2)};  // robot 1 on its way
  robot0.Tick(PoseAt(7.0, 7.0), heard, 1, &out);
  ASSERT_EQ(Phases(out), std::vector<std::string>{"GATHERING"});
  ASSERT_TRUE(robot0.IsFirstLeaderOfAny());
  robot0.OnStatus(7, MissionPhase::kGathering, {0});
  EXPECT_FALSE(robot0.IsFirstLeaderOfAny());
  EXPECT_EQ(robot0.LostOf(7), (std::set<std::uint16_t>{0}));
  out = MissionOutbox();
  MissionPlan plan = robot0.Tick(PoseAt(7.0, 7.0), heard, 2, &out);
  EXPECT_TRUE(out.empty());  // it says nothing more of the mission
  // It is no member any more: it leaves the mission (no carry), and the object is a danger
  // zone for it, as any other mission's.
  EXPECT_FALSE(plan.active.has_value());
  EXPECT_FALSE(plan.carry.has_value());
  ASSERT_EQ(plan.zones.size(), 1u);
  EXPECT_EQ(plan.zones[0].id, 7);
  EXPECT_FALSE(plan.zones[0].inverted);
  // Robots of other missions and unknown ones in the list change nothing.
  robot0.OnStatus(7, MissionPhase::kGathering, {0, 40});
  EXPECT_EQ(robot0.LostOf(7), (std::set<std::uint16_t>{0}));

  // Robot 2 heard robot 0 but not robot 1 (lost at tick 7); robot 0's lost list promotes it.
  MissionAgent robot2(2, params);
  ASSERT_TRUE(robot2.OnNewMission(Thesis(), &why)) << why;
  robot2.OnStatus(7, MissionPhase::kGathering, {});
  for (std::uint64_t t = 1; t <= 7; ++t) {
    out = MissionOutbox();
    robot2.Tick(PoseAt(7.2, 7.2), {At(0, 7.0, 7.0)}, t, &out);
    ASSERT_TRUE(out.empty());
  }
  ASSERT_EQ(robot2.LostOf(7), (std::set<std::uint16_t>{1}));
  ASSERT_FALSE(robot2.IsFirstLeaderOfAny());
  robot2.OnStatus(7, MissionPhase::kGathering, {0});
  EXPECT_TRUE(robot2.IsFirstLeaderOfAny());
  out = MissionOutbox();
  robot2.Tick(PoseAt(7.2, 7.2), {At(0, 7.0, 7.0)}, 8, &out);
  ASSERT_FALSE(out.statuses.empty());
  EXPECT_NE(out.statuses[0].reason.find("robot 2 leads: robot(s) 0, 1 lost"), std::string::npos)
      << out.statuses[0].reason;
  EXPECT_EQ(out.statuses[0].lost, (std::vector<std::uint16_t>{0, 1}));
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
