// The lock-step relay of mission messages and the relayed positions (sim/mission_relay.h), seen
// through the messages a round and an answer become (ros/common/conversions.h): every robot's
// round carries the same messages, ordered by sender, whatever order they arrived in; orders
// wait for their start tick.
#include "swarm_transport/sim/mission_relay.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "status_fixture.h"
#include "swarm_transport/ros/common/conversions.h"

namespace swarm_transport {
namespace {

using sim::AnswerSender;

// The relay as the simulator uses it: messages converted at its edge.
class MissionRelay {
 public:
  void AddOrder(const std::string& sender, const New_Mission& m) {
    relay_.AddOrder(sender, ToMissionSpec(m), m.start_tick);
  }
  template <typename M>
  void Add(const std::string& sender, const M& m) {
    relay_.Add(sender, ToMissionMessage(m));
  }
  void AddAnswer(std::uint16_t id, const Tick_Answer& a) { relay_.AddAnswer(id, ToAnswer(a)); }
  std::vector<New_Mission> ReleaseOrders(std::uint64_t tick) {
    std::vector<New_Mission> out;
    for (const core::MissionSpec& spec : relay_.ReleaseOrders(tick))
      out.push_back(ToNewMission(spec));
    return out;
  }
  void Fill(Neighbors* msg) {
    core::Round round = ToRound(*msg);
    relay_.Fill(&round);
    *msg = ToNeighbors(round);
  }
  void FillStanding(Neighbors* msg) const {
    core::Round round = ToRound(*msg);
    relay_.FillStanding(&round);
    *msg = ToNeighbors(round);
  }
  std::size_t standing_orders() const { return relay_.standing_orders(); }
  std::size_t held_orders() const { return relay_.held_orders(); }
  void Clear() { relay_.Clear(); }

 private:
  sim::MissionRelay relay_;
};

using fixtures::Status;

New_Mission Order(std::uint16_t id, std::uint64_t start_tick) {
  New_Mission m;
  m.mission_id = id;
  m.start_tick = start_tick;
  return m;
}

TEST(MissionRelayTest, AnswerSendersSortAfterNodesByRobotId) {
  EXPECT_EQ(AnswerSender(7), "robot_00007");
  EXPECT_LT(std::string("/mission_dispatcher"), AnswerSender(0));
  EXPECT_LT(AnswerSender(9), AnswerSender(10));
  EXPECT_LT(AnswerSender(65534), AnswerSender(65535));
}

// The order a round lists messages in does not depend on which process's message arrived
// first: by sender, and per sender in arrival order.
TEST(MissionRelayTest, RoundListsEachKindBySenderThenArrival) {
  MissionRelay relay;
  Tick_Answer robot12;
  robot12.statuses = {Status(1, Mission_Status::LOADING)};
  Tick_Answer robot3;
  robot3.statuses = {Status(2, Mission_Status::GATHERING), Status(2, Mission_Status::LOADING)};
  robot3.statuses[1].lost = {0, 4};  // the robots its first leader counts lost travel with it
  relay.AddAnswer(12, robot12);
  relay.Add("/test", Status(3, Mission_Status::QUEUED));
  relay.AddAnswer(3, robot3);
  Neighbors round;
  relay.Fill(&round);
  ASSERT_EQ(round.statuses.size(), 4u);
  EXPECT_EQ(round.statuses[0].mission_id, 3);  // "/test"
  EXPECT_EQ(round.statuses[1].mission_id, 2);  // robot 3, in its order
  EXPECT_EQ(round.statuses[1].state, Mission_Status::GATHERING);
  EXPECT_EQ(round.statuses[2].state, Mission_Status::LOADING);
  EXPECT_EQ(round.statuses[2].lost, (std::vector<std::uint16_t>{0, 4}));
  EXPECT_TRUE(round.statuses[1].lost.empty());
  const core::Round taken = ToRound(round);
  const auto* phase = std::get_if<core::PhaseStatus>(&taken.messages.back());
  ASSERT_NE(phase, nullptr);
  EXPECT_EQ(phase->lost, (std::vector<std::uint16_t>{}));  // robot 12's, last
  EXPECT_EQ(std::get<core::PhaseStatus>(taken.messages[taken.messages.size() - 2]).lost,
            (std::vector<std::uint16_t>{0, 4}));
  EXPECT_EQ(round.statuses[3].mission_id, 1);  // robot 12
  // A second robot's round of the same tick gets the same lists.
  Neighbors other;
  relay.Fill(&other);
  EXPECT_EQ(other.statuses, round.statuses);
  // A message added after a Fill is in the next Fill (the sorted copy is not stale).
  relay.Add("/a", Status(9, Mission_Status::DONE));
  relay.Fill(&other);
  ASSERT_EQ(other.statuses.size(), 5u);
  EXPECT_EQ(other.statuses[0].mission_id, 9);
  // The next tick starts empty.
  relay.Clear();
  Neighbors next;
  relay.Fill(&next);
  EXPECT_TRUE(next.statuses.empty());
}

TEST(MissionRelayTest, AnswerCarriesEveryKindButProgress) {
  MissionRelay relay;
  Tick_Answer a;
  a.object_updates.resize(1);
  a.freezes.resize(2);
  a.continues.resize(1);
  a.object_deletes.resize(1);
  a.statuses.resize(1);
  a.progress.resize(3);
  relay.AddAnswer(5, a);
  Neighbors round;
  relay.Fill(&round);
  EXPECT_EQ(round.object_updates.size(), 1u);
  EXPECT_EQ(round.freezes.size(), 2u);
  EXPECT_EQ(round.continues.size(), 1u);
  EXPECT_EQ(round.object_deletes.size(), 1u);
  EXPECT_EQ(round.statuses.size(), 1u);
  EXPECT_TRUE(round.missions.empty());
}

TEST(MissionRelayTest, OrdersWaitForTheirStartTick) {
  MissionRelay relay;
  relay.AddOrder("/mission_dispatcher", Order(1, 5));
  relay.AddOrder("/mission_dispatcher", Order(2, 0));
  relay.AddOrder("/mission_dispatcher", Order(3, 3));
  std::vector<New_Mission> due = relay.ReleaseOrders(0);
  ASSERT_EQ(due.size(), 1u);
  EXPECT_EQ(due[0].mission_id, 2);
  Neighbors round;
  relay.Fill(&round);
  ASSERT_EQ(round.missions.size(), 1u);
  relay.Clear();
  EXPECT_EQ(relay.held_orders(), 2u);
  EXPECT_TRUE(relay.ReleaseOrders(2).empty());
  due = relay.ReleaseOrders(5);  // both due: arrival order
  ASSERT_EQ(due.size(), 2u);
  EXPECT_EQ(due[0].mission_id, 1);
  EXPECT_EQ(due[1].mission_id, 3);
  EXPECT_EQ(relay.held_orders(), 0u);
  relay.Fill(&round);
  EXPECT_EQ(round.missions.size(), 2u);
}

// A robot whose process connects late gets, in its first round, the orders sent before that
// whose missions have not ended, their objects where last reported, with their latest phase;
// never twice, never an ended one.
TEST(MissionRelayTest, AConnectingRobotGetsTheOrdersOfTheMissionsThatHaveNotEnded) {
  MissionRelay relay;
  for (std::uint16_t id : {1, 2, 3, 4, 5}) relay.AddOrder("/mission_dispatcher", Order(id, 0));
  relay.AddOrder("/mission_dispatcher", Order(6, 9));  // held until tick 9
  ASSERT_EQ(relay.ReleaseOrders(1).size(), 5u);
  relay.Clear();
  EXPECT_EQ(relay.standing_orders(), 5u);
  Tick_Answer leader;
  leader.statuses = {Status(1, Mission_Status::QUEUED),
                     Status(1, Mission_Status::GATHERING),
                     Status(1, Mission_Status::TRANSPORT),
                     Status(2, Mission_Status::DONE),
                     Status(3, Mission_Status::ABORTED),
                     Status(1, Mission_Status::LOADING)};  // late: not back to LOADING
  Update_Object moved;
  moved.mission_id = 1;
  moved.object_position_x = 4.5f;
  moved.object_position_y = 5.5f;
  leader.object_updates = {moved};
  relay.AddAnswer(7, leader);
  Delete_Object gone;
  gone.mission_id = 4;
  relay.Add("/mission_dispatcher", gone);
  relay.Add("/mission_dispatcher", Status(5, Mission_Status::REJECTED));  // never started
  EXPECT_EQ(relay.standing_orders(), 1u);
  // A dispatcher's REJECTED of a refused duplicate of a started mission's id ends nothing.
  relay.Add("/mission_dispatcher", Status(1, Mission_Status::REJECTED));
  EXPECT_EQ(relay.standing_orders(), 1u);
  relay.Clear();

  Neighbors round;
  relay.Fill(&round);
  EXPECT_TRUE(round.missions.empty());
  relay.FillStanding(&round);
  ASSERT_EQ(round.missions.size(), 1u);
  EXPECT_EQ(round.missions[0].mission_id, 1);
  EXPECT_FLOAT_EQ(round.missions[0].object_position_x, 4.5f);
  EXPECT_FLOAT_EQ(round.missions[0].object_position_y, 5.5f);
  ASSERT_EQ(round.statuses.size(), 1u);
  EXPECT_EQ(round.statuses[0].state, Mission_Status::TRANSPORT);
  EXPECT_TRUE(round.statuses[0].lost.empty());

  // Released in this very round: not twice; nor its phase when the round has one of it.
  relay.AddOrder("/mission_dispatcher", Order(8, 0));
  ASSERT_EQ(relay.ReleaseOrders(2).size(), 1u);
  Tick_Answer promoted;  // a first leader promoted over robot 7, then one that lost robot 3
  promoted.statuses = {Status(1, Mission_Status::TRANSPORT)};
  promoted.statuses[0].lost = {7};
  relay.AddAnswer(8, promoted);
  promoted.statuses[0].lost = {3, 7};
  relay.AddAnswer(8, promoted);
  relay.Add("/mission_dispatcher", Status(1, Mission_Status::UNLOADING));
  Neighbors joining;
  relay.Fill(&joining);
  relay.FillStanding(&joining);
  ASSERT_EQ(joining.missions.size(), 2u);
  EXPECT_EQ(joining.missions[0].mission_id, 8);
  EXPECT_EQ(joining.missions[1].mission_id, 1);
  ASSERT_EQ(joining.statuses.size(), 3u);  // this round's own: not the standing phase again
  EXPECT_EQ(joining.statuses.front().state, Mission_Status::UNLOADING);  // the dispatcher's
  // A second order with a started mission's id is a duplicate: the mission keeps its order.
  relay.Clear();
  New_Mission duplicate = Order(1, 0);
  duplicate.target_x = 9.0f;
  relay.AddOrder("/test", duplicate);
  ASSERT_EQ(relay.ReleaseOrders(3).size(), 1u);
  relay.Clear();
  Neighbors later;
  relay.FillStanding(&later);
  ASSERT_EQ(later.missions.size(), 2u);
  EXPECT_EQ(later.missions[0].mission_id, 1);
  // Its standing phase names every robot its statuses named lost: a robot started again under
  // a lost robot's id learns it was lost there.
  ASSERT_EQ(later.statuses.size(), 1u);
  EXPECT_EQ(later.statuses[0].state, Mission_Status::UNLOADING);
  EXPECT_EQ(later.statuses[0].lost, (std::vector<std::uint16_t>{3, 7}));
  EXPECT_FLOAT_EQ(later.missions[0].target_x, 0.0f);
  EXPECT_FLOAT_EQ(later.missions[0].object_position_x, 4.5f);
}

Robot_Position Position(std::uint16_t robot, std::uint8_t sub, std::uint8_t type, double x) {
  Robot_Position p;
  p.robot_id = robot;
  p.sub_id = sub;
  p.type = type;
  p.pos_x = x;
  p.pos_y = 1.0;
  p.angle = 0.0f;
  return p;
}

// The relayed positions as the simulator takes them from /flock/position.
class RelayedPositions {
 public:
  std::string Take(const Robot_Position& p) { return relayed_.Take(ToPosition(p)); }
  std::size_t size() const { return relayed_.size(); }
  std::vector<sim::RadioExtra> Extras() const { return relayed_.Extras(); }
  std::vector<Robot_Position> AtOwners(const std::vector<long>& owner,
                                       const std::vector<Robot_Position>& truth) const {
    std::vector<core::Position> t;
    for (const Robot_Position& p : truth) t.push_back(ToPosition(p));
    return ToRobotPositions(relayed_.AtOwners(owner, t));
  }
  void EraseCopiesOf(std::uint16_t id) { relayed_.EraseCopiesOf(id); }
  bool Erase(std::uint16_t id, std::uint8_t sub) { return relayed_.Erase(id, sub); }

 private:
  sim::RelayedPositions relayed_;
};

TEST(RelayedPositionsTest, KeepsCopiesAndStatistsAndRejectsBadOnes) {
  RelayedPositions relayed;
  EXPECT_EQ(relayed.Take(Position(1, 0, Robot_Position::TYPE_PHYSICAL, 2.0)), "");
  EXPECT_EQ(relayed.size(), 0u);  // the world's truth is relayed, not announcements
  EXPECT_NE(relayed.Take(Position(1, 1, Robot_Position::TYPE_VIRTUAL,
                                  std::numeric_limits<double>::quiet_NaN())),
            "");
  EXPECT_NE(relayed.Take(Position(1, 1, 9, 2.0)).find("unknown type 9"), std::string::npos);
  EXPECT_EQ(relayed.size(), 0u);
  Robot_Position turned = Position(1, 1, Robot_Position::TYPE_VIRTUAL, 2.0);
  turned.angle = -90.0f;
  EXPECT_EQ(relayed.Take(turned), "");
  EXPECT_EQ(relayed.Take(Position(4, 1, Robot_Position::TYPE_STATIST, 3.0)), "");
  EXPECT_EQ(relayed.Take(Position(1, 2, Robot_Position::TYPE_STATIST, 5.0)), "");
  ASSERT_EQ(relayed.size(), 3u);
  const std::vector<sim::RadioExtra> extras = relayed.Extras();
  ASSERT_EQ(extras.size(), 3u);
  EXPECT_TRUE(extras[0].virtual_copy);  // (1, 1)
  EXPECT_EQ(extras[0].owner, 1);
  EXPECT_FALSE(extras[1].virtual_copy);         // (1, 2)
  EXPECT_DOUBLE_EQ(extras[2].position.x, 3.0);  // (4, 1)

  // A virtual copy is relayed at its owner's true pose, the others where announced.
  std::vector<Robot_Position> truth = {Position(1, 0, Robot_Position::TYPE_PHYSICAL, 7.0)};
  truth[0].angle = 45.0f;
  const std::vector<Robot_Position> at = relayed.AtOwners({0, -1, -1}, truth);
  ASSERT_EQ(at.size(), 3u);
  EXPECT_DOUBLE_EQ(at[0].pos_x, 7.0);
  EXPECT_FLOAT_EQ(at[0].angle, 45.0f);
  EXPECT_DOUBLE_EQ(at[1].pos_x, 5.0);
  // Without its owner the copy stands where announced, its angle kept in [0, 360).
  const std::vector<Robot_Position> alone = relayed.AtOwners({-1, -1, -1}, truth);
  EXPECT_DOUBLE_EQ(alone[0].pos_x, 2.0);
  EXPECT_FLOAT_EQ(alone[0].angle, 270.0f);

  // A killed robot's copies die with it; its statists and others stay.
  relayed.EraseCopiesOf(1);
  EXPECT_EQ(relayed.size(), 2u);
  relayed.Erase(4, 1);
  EXPECT_EQ(relayed.size(), 1u);
}

// Live tuning (issue 13): an accepted change goes out with the next round, in every round from
// then on, numbered; a bad one is refused with the key named and changes nothing.
TEST(TuningRelayTest, AnAcceptedChangeGoesOutWithTheNextRoundAndABadOneChangesNothing) {
  core::SwarmConfig config;
  config.flocking.free_will_deg = 90.0;
  config.flocking.cohesion = 0.05;
  sim::TuningRelay relay(config);
  core::Round round;
  relay.Fill(&round);
  EXPECT_FALSE(round.tuning.has_value());  // nothing before the first change
  // The values in use change nothing (dynamic_reconfigure's first call).
  EXPECT_EQ(relay.Propose(core::FlockingTuning::Of(config.flocking)), "");
  EXPECT_FALSE(relay.BeginRound(3).has_value());

  core::FlockingTuning calm = core::FlockingTuning::Of(config.flocking);
  calm.free_will_deg = 45.0;
  EXPECT_EQ(relay.Propose(calm), "");
  relay.Fill(&round);
  EXPECT_FALSE(round.tuning.has_value()) << "not before its round";
  const std::optional<core::TuningGeneration> first = relay.BeginRound(7);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->generation, 1u);
  EXPECT_EQ(first->tick, 7u);
  EXPECT_DOUBLE_EQ(first->tuning.free_will_deg, 45.0);
  EXPECT_DOUBLE_EQ(first->tuning.cohesion, 0.05);
  EXPECT_FALSE(relay.BeginRound(8).has_value()) << "returned once";
  for (std::uint64_t tick : {8u, 100u}) {
    relay.Fill(&round);  // every later round carries it (a robot that joins later too)
    ASSERT_TRUE(round.tuning.has_value()) << tick;
    EXPECT_EQ(round.tuning->tick, 7u);
    EXPECT_EQ(ToNeighbors(round).tuning.size(), 1u);
  }

  core::FlockingTuning bad = calm;
  bad.free_will_deg = 400.0;
  EXPECT_NE(relay.Propose(bad).find("free_will_deg must be in [0, 360] but is 400"),
            std::string::npos);
  bad = calm;
  bad.speed_m_per_tick = 1.5;  // beyond the local range of 1 m
  EXPECT_NE(relay.Propose(bad).find("speed_m_per_tick"), std::string::npos);
  bad = calm;
  bad.cohesion = std::numeric_limits<double>::quiet_NaN();
  EXPECT_NE(relay.Propose(bad).find("cohesion"), std::string::npos);
  EXPECT_TRUE(relay.newest() == calm);
  EXPECT_FALSE(relay.BeginRound(9).has_value());
  EXPECT_EQ(relay.generation(), 1u);

  // Two changes before a round: the last counts; one changed back is no new generation.
  core::FlockingTuning wide = calm;
  wide.local_range_m = 2.0;
  wide.speed_m_per_tick = 0.2;
  EXPECT_EQ(relay.Propose(wide), "");
  EXPECT_EQ(relay.Propose(calm), "");
  EXPECT_FALSE(relay.BeginRound(10).has_value());
  EXPECT_EQ(relay.Propose(wide), "");
  const std::optional<core::TuningGeneration> second = relay.BeginRound(11);
  ASSERT_TRUE(second.has_value());
  EXPECT_EQ(second->generation, 2u);
  EXPECT_DOUBLE_EQ(second->tuning.local_range_m, 2.0);
  EXPECT_DOUBLE_EQ(relay.config().flocking.speed_m_per_tick, 0.2);
}

}  // namespace
}  // namespace swarm_transport
