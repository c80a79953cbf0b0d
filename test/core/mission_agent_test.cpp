// The robot side of missions: zones, roles, FIFO, and the first leader's phase machine.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "swarm_transport/core/mission_agent.h"

namespace swarm_transport {
namespace core {
namespace {

// Robots [0, 3), 1 leader, a 2x2 object at (7, 7) carried to (3, 3).
MissionSpec Thesis(std::uint16_t id = 7) {
  MissionSpec m;
  m.id = id;
  m.range_from = 0;
  m.range_to = 3;
  m.leader_number = 1;
  m.object_centre = {7.0, 7.0};
  m.object_size = {2.0, 2.0};
  m.target = {3.0, 3.0};
  return m;
}

Neighbour At(std::uint16_t id, double x, double y) {
  Neighbour n;
  n.id = id;
  n.position = {x, y};
  return n;
}

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
  ASSERT_EQ(m.zones.size(), 1u);
  EXPECT_TRUE(m.zones[0].inverted);
  EXPECT_TRUE(m.zones[0].Forbids({1.0, 1.0}));  // outside its object: it must get in
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
  EXPECT_TRUE(plan.lead);
  EXPECT_NEAR(plan.steer.degrees(), 225.0, 1e-9);
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

TEST(MissionAgentTest, ALeaderCarryingItsObjectIsNotKeptInsideIt) {
  MissionAgent leader(0, MissionAgentParams());
  IntoTransport(&leader);
  MissionOutbox out;
  // Far ahead of the centroid: no safety zone holds it back, it steers centre -> target.
  const MissionPlan plan =
      leader.Tick(PoseAt(4.0, 4.0), {At(1, 6.0, 6.0), At(2, 5.0, 5.0)}, 11, &out);
  EXPECT_TRUE(plan.lead);
  EXPECT_TRUE(plan.zones.empty());
  // A passive robot of the mission keeps the object as its safety zone.
  MissionAgent passive(1, MissionAgentParams());
  std::string why;
  ASSERT_TRUE(passive.OnNewMission(Thesis(), &why));
  const MissionPlan p = passive.Tick(PoseAt(7.0, 7.0), {}, 11, nullptr);
  ASSERT_EQ(p.zones.size(), 1u);
  EXPECT_TRUE(p.zones[0].inverted);
}

TEST(MissionAgentTest, FirstLeaderDocksTheObjectAloneNearTheTarget) {
  MissionAgentParams params;
  params.docking_radius_m = 0.2;
  params.docking_patience_ticks = 5;
  MissionAgent leader(1, params);  // first leader in the middle of robots [1, 4)
  std::string why;
  MissionSpec spec = Thesis();
  spec.range_from = 1;
  spec.range_to = 4;
  ASSERT_TRUE(leader.OnNewMission(spec, &why));
  MissionOutbox out;
  leader.Tick(PoseAt(7.0, 7.0), {At(2, 7.5, 7.5), At(3, 6.5, 6.5)}, 1, &out);
  ASSERT_TRUE(leader.OnEvent(7, MissionEventKind::kLoaded, 0, &why)) << why;
  out = MissionOutbox();
  leader.Tick(PoseAt(7.0, 7.0), {At(2, 7.5, 7.5), At(3, 6.5, 6.5)}, 2, &out);
  ASSERT_EQ(Phases(out), std::vector<std::string>{"TRANSPORT"});
  // 0.3 m away: the swarm carries on.
  out = MissionOutbox();
  leader.Tick(PoseAt(3.3, 3.0), {At(2, 3.8, 3.5), At(3, 2.8, 2.5)}, 3, &out);
  EXPECT_TRUE(out.freeze.empty());
  // 0.15 m away (centroid (3.15, 3.0)): the others [2, 4) stand, the leader aims three times
  // as far as the object must go.
  out = MissionOutbox();
  MissionPlan plan = leader.Tick(PoseAt(3.15, 3.0), {At(2, 3.65, 3.5), At(3, 2.65, 2.5)}, 4, &out);
  ASSERT_EQ(out.freeze.size(), 1u);
  EXPECT_EQ(out.freeze[0], std::make_pair(std::uint16_t{2}, std::uint16_t{4}));
  EXPECT_TRUE(plan.lead);
  EXPECT_NEAR(plan.goal.x, 3.15 - 3 * 0.15, 1e-9);
  EXPECT_NEAR(plan.goal.y, 3.0, 1e-9);
  EXPECT_NEAR(plan.steer.degrees(), 180.0, 1e-9);
  // No progress for more than 5 ticks (since tick 4): the others continue at tick 10, no
  // docking again before tick 15.
  for (std::uint64_t t = 5; t <= 9; ++t) {
    out = MissionOutbox();
    leader.Tick(PoseAt(3.15, 3.0), {At(2, 3.65, 3.5), At(3, 2.65, 2.5)}, t, &out);
    EXPECT_TRUE(out.resume.empty()) << t;
  }
  out = MissionOutbox();
  plan = leader.Tick(PoseAt(3.15, 3.0), {At(2, 3.65, 3.5), At(3, 2.65, 2.5)}, 10, &out);
  ASSERT_EQ(out.resume.size(), 1u);
  EXPECT_EQ(out.resume[0], std::make_pair(std::uint16_t{2}, std::uint16_t{4}));
  EXPECT_NEAR(plan.goal.x, 3.0 + (3.15 - 3.15), 1e-9);  // plain goal again: target + offset
  out = MissionOutbox();
  leader.Tick(PoseAt(3.14, 3.0), {At(2, 3.64, 3.5), At(3, 2.64, 2.5)}, 14, &out);
  EXPECT_TRUE(out.freeze.empty());
  out = MissionOutbox();
  leader.Tick(PoseAt(3.14, 3.0), {At(2, 3.64, 3.5), At(3, 2.64, 2.5)}, 16, &out);
  EXPECT_EQ(out.freeze.size(), 1u);
  // Arrival: every robot freezes for unloading.
  out = MissionOutbox();
  leader.Tick(PoseAt(3.01, 3.0), {At(2, 3.51, 3.5), At(3, 2.51, 2.5)}, 17, &out);
  EXPECT_EQ(Phases(out), std::vector<std::string>{"UNLOADING"});
  ASSERT_EQ(out.freeze.size(), 1u);
  EXPECT_EQ(out.freeze[0], std::make_pair(std::uint16_t{1}, std::uint16_t{4}));
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
  ASSERT_EQ(plan.zones.size(), 1u);
  EXPECT_TRUE(plan.zones[0].shape.Contains({7.0, 7.0}));
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

}  // namespace
}  // namespace core
}  // namespace swarm_transport
