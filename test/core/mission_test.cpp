// MissionSpec and ValidateMission [SPEC 6, 10]: the group, its leaders, and every rejection.
#include "swarm_transport/core/mission.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace swarm_transport {
namespace core {
namespace {

using Ids = std::vector<std::uint16_t>;
using Runs = std::vector<std::pair<std::uint16_t, std::uint16_t>>;

// The thesis mission [T7.4]: robots [0, 12), 3 leaders, a 2 x 2 object at (7, 7) to (3, 3).
MissionSpec ThesisMission() {
  MissionSpec m;
  m.id = 7;
  m.range_from = 0;
  m.range_to = 12;
  m.leader_number = 3;
  m.object_centre = {7.0, 7.0};
  m.object_size = {2.0, 2.0};
  m.target = {3.0, 3.0};
  m.transport_mode = 0;
  return m;
}

// Robot 4 alone drives to (9, 9) [T5.3].
MissionSpec LeaderOnlyMission() {
  MissionSpec m;
  m.id = 8;
  m.range_from = 4;
  m.range_to = 5;
  m.leader_number = 1;
  m.target = {9.0, 9.0};
  return m;
}

MissionContext Context() {
  MissionContext c;
  c.world_size_m = 11.088889;
  return c;
}

// The reason must be non-empty and mention `word`, so that the log line says what is wrong.
void ExpectRejected(const MissionSpec& m, const MissionContext& c, const std::string& word) {
  const std::string reason = ValidateMission(m, c);
  EXPECT_FALSE(reason.empty()) << "expected a rejection mentioning '" << word << "'";
  EXPECT_NE(reason.find(word), std::string::npos) << "reason: " << reason;
}

TEST(MissionSpecTest, AssignedFromRangeIsHalfOpen) {
  const MissionSpec m = ThesisMission();
  EXPECT_EQ(m.Assigned(), (Ids{0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11}));
  EXPECT_TRUE(m.Assigns(0));
  EXPECT_TRUE(m.Assigns(11));
  EXPECT_FALSE(m.Assigns(12));
}

TEST(MissionSpecTest, AssignedFromRobotIdsIsSortedUniqueAndReplacesTheRange) {
  MissionSpec m = ThesisMission();
  m.robot_ids = {9, 1, 4, 9};
  EXPECT_EQ(m.Assigned(), (Ids{1, 4, 9}));
  EXPECT_TRUE(m.Assigns(4));
  EXPECT_FALSE(m.Assigns(0));  // in the range, but robot_ids replaces it
  EXPECT_FALSE(m.Assigns(5));
}

TEST(MissionSpecTest, EmptyRangeAssignsNobody) {
  MissionSpec m = ThesisMission();
  m.range_from = 5;
  m.range_to = 5;
  EXPECT_TRUE(m.Assigned().empty());
  EXPECT_EQ(m.FirstLeader(), 0);
}

TEST(MissionSpecTest, LeadersAreTheLowestAssignedIds) {
  const MissionSpec m = ThesisMission();
  EXPECT_EQ(m.Leaders(), (Ids{0, 1, 2}));
  EXPECT_EQ(m.FirstLeader(), 0);
  EXPECT_TRUE(m.IsLeader(2));
  EXPECT_FALSE(m.IsLeader(3));
}

TEST(MissionSpecTest, LeadersFromRobotIds) {
  MissionSpec m = ThesisMission();
  m.robot_ids = {8, 3, 7, 1};
  m.leader_number = 2;
  EXPECT_EQ(m.Leaders(), (Ids{1, 3}));
  EXPECT_EQ(m.FirstLeader(), 1);
  EXPECT_TRUE(m.IsLeader(3));
  EXPECT_FALSE(m.IsLeader(7));
}

TEST(MissionSpecTest, AssignedRunsCoverTheIdsWithMaximalHalfOpenRanges) {
  MissionSpec m = ThesisMission();
  m.robot_ids = {1, 2, 3, 7, 8};
  EXPECT_EQ(m.AssignedRuns(), (Runs{{1, 4}, {7, 9}}));
  m.robot_ids = {8, 7, 3, 2, 1, 2};  // order and duplicates do not matter
  EXPECT_EQ(m.AssignedRuns(), (Runs{{1, 4}, {7, 9}}));
  m.robot_ids.clear();
  EXPECT_EQ(m.AssignedRuns(), (Runs{{0, 12}}));
}

TEST(MissionSpecTest, LeaderOnlyMeansAZeroByZeroObject) {
  EXPECT_TRUE(LeaderOnlyMission().LeaderOnly());
  EXPECT_FALSE(ThesisMission().LeaderOnly());
  MissionSpec m = ThesisMission();
  m.object_size = {0.0, 2.0};  // zero on one axis only is a bad transport, not leader-only
  EXPECT_FALSE(m.LeaderOnly());
}

TEST(MissionSpecTest, PhaseNames) {
  EXPECT_STREQ(PhaseName(MissionPhase::kQueued), "QUEUED");
  EXPECT_STREQ(PhaseName(MissionPhase::kGathering), "GATHERING");
  EXPECT_STREQ(PhaseName(MissionPhase::kLoading), "LOADING");
  EXPECT_STREQ(PhaseName(MissionPhase::kTransport), "TRANSPORT");
  EXPECT_STREQ(PhaseName(MissionPhase::kUnloading), "UNLOADING");
  EXPECT_STREQ(PhaseName(MissionPhase::kDone), "DONE");
  EXPECT_STREQ(PhaseName(MissionPhase::kAborted), "ABORTED");
  EXPECT_STREQ(PhaseName(MissionPhase::kRejected), "REJECTED");
  EXPECT_STREQ(PhaseName(static_cast<MissionPhase>(42)), "UNKNOWN");
}

TEST(ValidateMissionTest, AcceptsTheThesisMission) {
  EXPECT_EQ(ValidateMission(ThesisMission(), Context()), "");
}

TEST(ValidateMissionTest, AcceptsALeaderOnlyMission) {
  EXPECT_EQ(ValidateMission(LeaderOnlyMission(), Context()), "");
}

TEST(ValidateMissionTest, AcceptsFormationModeAndTheArenaBorder) {
  MissionSpec m = ThesisMission();
  m.transport_mode = 1;
  m.target = {0.0, 11.088889};  // on the border is inside
  EXPECT_EQ(ValidateMission(m, Context()), "");
}

TEST(ValidateMissionTest, RejectsNonFiniteFields) {
  MissionSpec m = ThesisMission();
  m.all_finite = false;
  ExpectRejected(m, Context(), "finite");
}

TEST(ValidateMissionTest, RejectsAnEmptyOrInvertedRange) {
  MissionSpec m = ThesisMission();
  m.range_from = 12;
  m.range_to = 12;
  ExpectRejected(m, Context(), "from must be < to");
  m.range_from = 12;
  m.range_to = 3;
  ExpectRejected(m, Context(), "from must be < to");
}

TEST(ValidateMissionTest, RobotIdsMakeTheRangeIrrelevant) {
  MissionSpec m = ThesisMission();
  m.range_from = 12;
  m.range_to = 3;
  m.robot_ids = {1, 2, 3, 7, 8};
  EXPECT_EQ(ValidateMission(m, Context()), "");
}

TEST(ValidateMissionTest, RejectsZeroLeaders) {
  MissionSpec m = ThesisMission();
  m.leader_number = 0;
  ExpectRejected(m, Context(), "leader_number must be >= 1");
}

TEST(ValidateMissionTest, RejectsMoreLeadersThanRobots) {
  MissionSpec m = ThesisMission();
  m.leader_number = 13;
  ExpectRejected(m, Context(), "larger than the group of 12");
  m.robot_ids = {1, 1, 2};  // duplicates count once
  m.leader_number = 3;
  ExpectRejected(m, Context(), "larger than the group of 2");
}

TEST(MissionSpecTest, LeaderIdsNameTheLeaders) {
  MissionSpec m = ThesisMission();
  m.robot_ids = {8, 3, 7, 1};
  m.leader_number = 2;
  m.leader_ids = {8, 3};  // any order
  EXPECT_EQ(m.Leaders(), (Ids{3, 8}));
  EXPECT_EQ(m.FirstLeader(), 3);
  EXPECT_TRUE(m.IsLeader(8));
  EXPECT_FALSE(m.IsLeader(1));
  EXPECT_EQ(m.LeadOrder(), (Ids{3, 8, 1, 7}));
  EXPECT_EQ(ValidateMission(m, Context()), "");
  m.leader_ids.clear();  // the old rule: the lowest
  EXPECT_EQ(m.Leaders(), (Ids{1, 3}));
  EXPECT_EQ(m.LeadOrder(), (Ids{1, 3, 7, 8}));
}

TEST(ValidateMissionTest, RejectsLeaderIdsThatAreNotLeaderNumberAssignedRobots) {
  MissionSpec m = ThesisMission();  // robots [0, 12), 3 leaders
  m.leader_ids = {4, 9, 11};
  EXPECT_EQ(ValidateMission(m, Context()), "");
  m.leader_ids = {4, 9};
  ExpectRejected(m, Context(), "leader_ids names 2 robots but leader_number is 3");
  m.leader_ids = {4, 9, 11, 2};
  ExpectRejected(m, Context(), "leader_ids names 4 robots but leader_number is 3");
  m.leader_ids = {4, 9, 4};
  ExpectRejected(m, Context(), "leader_ids names robot 4 twice");
  m.leader_ids = {4, 9, 12};
  ExpectRejected(m, Context(), "leader_ids names robot 12, which the mission does not assign");
  m.robot_ids = {1, 2, 3};
  m.leader_ids = {1, 2, 7};
  ExpectRejected(m, Context(), "robot 7, which the mission does not assign");
}

TEST(ValidateMissionTest, RejectsAnUnknownTransportMode) {
  MissionSpec m = ThesisMission();
  m.transport_mode = 2;
  ExpectRejected(m, Context(), "transport_mode");
}

TEST(ValidateMissionTest, RejectsAnObjectSizeNotAboveZero) {
  MissionSpec m = ThesisMission();
  m.object_size = {2.0, 0.0};
  ExpectRejected(m, Context(), "object size");
  m.object_size = {-2.0, 2.0};
  ExpectRejected(m, Context(), "object size");
  m.object_size = {-1.0, -1.0};
  ExpectRejected(m, Context(), "object size");
}

TEST(ValidateMissionTest, RejectsALeaderOnlyMissionWithFollowers) {
  MissionSpec m = LeaderOnlyMission();
  m.range_to = 7;  // robots 4, 5, 6 but one leader
  ExpectRejected(m, Context(), "leader-only");
}

TEST(ValidateMissionTest, RejectsAnObjectOutsideTheArena) {
  MissionSpec m = ThesisMission();
  m.object_centre = {12.0, 7.0};
  ExpectRejected(m, Context(), "object centre");
  m.object_centre = {7.0, -0.1};
  ExpectRejected(m, Context(), "object centre");
}

TEST(ValidateMissionTest, IgnoresTheObjectPositionOfALeaderOnlyMission) {
  MissionSpec m = LeaderOnlyMission();
  m.object_centre = {-50.0, 99.0};
  EXPECT_EQ(ValidateMission(m, Context()), "");
}

TEST(ValidateMissionTest, RejectsATargetOutsideTheArena) {
  MissionSpec m = ThesisMission();
  m.target = {3.0, 11.2};
  ExpectRejected(m, Context(), "target");
  m = LeaderOnlyMission();
  m.target = {-1.0, 3.0};
  ExpectRejected(m, Context(), "target");
}

TEST(ValidateMissionTest, UsesTheContextsWorldSize) {
  MissionSpec m = ThesisMission();
  MissionContext c = Context();
  c.world_size_m = 5.0;
  ExpectRejected(m, c, "object centre");
  m.object_centre = {2.0, 2.0};
  m.target = {4.5, 4.5};
  EXPECT_EQ(ValidateMission(m, c), "");
}

TEST(ValidateMissionTest, RejectsADuplicateLiveId) {
  MissionContext c = Context();
  c.live_missions = {3, 7};
  ExpectRejected(ThesisMission(), c, "mission_id 7 is already live");
  c.live_missions = {3, 8};
  EXPECT_EQ(ValidateMission(ThesisMission(), c), "");
}

TEST(ValidateMissionTest, RejectsAnUnknownRobot) {
  MissionContext c = Context();
  for (std::uint16_t id = 0; id < 11; ++id) c.known_robots.insert(id);
  ExpectRejected(ThesisMission(), c, "robot 11 is unknown");
  c.known_robots.insert(11);
  EXPECT_EQ(ValidateMission(ThesisMission(), c), "");
}

TEST(ValidateMissionTest, SkipsTheRobotCheckWhenNoRobotIsKnown) {
  MissionSpec m = ThesisMission();
  m.robot_ids = {1000, 2000};
  m.leader_number = 1;
  EXPECT_EQ(ValidateMission(m, Context()), "");
}

TEST(ValidateMissionTest, ReportsTheFirstProblemOnly) {
  MissionSpec m = ThesisMission();
  m.all_finite = false;
  m.leader_number = 0;
  m.target = {-1.0, -1.0};
  const std::string reason = ValidateMission(m, Context());
  EXPECT_NE(reason.find("finite"), std::string::npos) << reason;
  EXPECT_EQ(reason.find("leader_number"), std::string::npos) << reason;
}

TEST(ValidateMissionTest, AnObjectLargerThanTheArenaIsRejected) {
  MissionSpec m = ThesisMission();
  m.object_size = {3e38, 2.0};  // as a forged order had it (issue 11)
  ExpectRejected(m, Context(), "larger than the arena");
  m.object_size = {2.0, 11.5};
  ExpectRejected(m, Context(), "larger than the arena");
  m.object_size = {11.0, 11.0};
  EXPECT_EQ(ValidateMission(m, Context()), "");
}

TEST(AdmitMissionTest, ValidatesThenHoldsTheLimitOfLiveMissions) {
  MissionContext c = Context();
  c.live_missions = {1, 2};
  c.max_live_missions = 3;
  EXPECT_EQ(AdmitMission(ThesisMission(), c), "");
  c.live_missions.insert(3);
  const std::string full = AdmitMission(ThesisMission(), c);
  EXPECT_NE(full.find("too many live missions (3"), std::string::npos) << full;
  // An invalid order is refused for what is wrong with it, full or not.
  MissionSpec bad = ThesisMission();
  bad.leader_number = 0;
  EXPECT_EQ(AdmitMission(bad, c), ValidateMission(bad, c));
  // 0: no limit (a robot under the dispatcher's admission).
  c.max_live_missions = 0;
  EXPECT_EQ(AdmitMission(ThesisMission(), c), "");
}

TEST(AdmissionTest, ParsesItsTwoNamesOnly) {
  Admission a = Admission::kRobots;
  EXPECT_TRUE(ParseAdmission("dispatcher", &a));
  EXPECT_EQ(a, Admission::kDispatcher);
  EXPECT_TRUE(ParseAdmission("robots", &a));
  EXPECT_EQ(a, Admission::kRobots);
  EXPECT_FALSE(ParseAdmission("Dispatcher", &a));
  EXPECT_EQ(a, Admission::kRobots);
  EXPECT_STREQ(AdmissionName(Admission::kDispatcher), "dispatcher");
}

TEST(AuthorityTest, OrdersCountFromTheDispatcherUnlessTheRobotsAdmit) {
  const Sender dispatcher{SenderKind::kDispatcher, 0};
  const Sender relay{SenderKind::kRelay, 0};
  const Sender robot{SenderKind::kRobot, 3};
  const Sender other{SenderKind::kOther, 0};
  EXPECT_TRUE(MayOrder(Admission::kDispatcher, dispatcher));
  EXPECT_TRUE(MayOrder(Admission::kDispatcher, relay));
  EXPECT_FALSE(MayOrder(Admission::kDispatcher, robot));
  EXPECT_FALSE(MayOrder(Admission::kDispatcher, other));
  EXPECT_TRUE(MayOrder(Admission::kRobots, other));
}

TEST(AuthorityTest, ReportsCountFromTheMissionsRobotsAndTheDispatcherOnly) {
  const MissionSpec m = ThesisMission();  // robots [0, 12)
  EXPECT_TRUE(MayReport(&m, Sender{SenderKind::kRobot, 0}));
  EXPECT_TRUE(MayReport(&m, Sender{SenderKind::kRobot, 11}));  // a promoted first leader
  EXPECT_FALSE(MayReport(&m, Sender{SenderKind::kRobot, 12}));
  EXPECT_TRUE(MayReport(&m, Sender{SenderKind::kDispatcher, 0}));
  EXPECT_TRUE(MayReport(&m, Sender{SenderKind::kRelay, 0}));
  EXPECT_FALSE(MayReport(&m, Sender{SenderKind::kOther, 0}));
  // Not known to the receiver: any robot's node counts, nobody else.
  EXPECT_TRUE(MayReport(nullptr, Sender{SenderKind::kRobot, 40}));
  EXPECT_FALSE(MayReport(nullptr, Sender{SenderKind::kOther, 0}));
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
