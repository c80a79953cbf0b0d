#include "swarm_transport/sim/heard_round.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <utility>
#include <vector>

#include "swarm_transport/core/mission.h"

namespace swarm_transport {
namespace sim {
namespace {

core::Position At(std::uint16_t id, float x, float y) {
  core::Position p;
  p.robot_id = id;
  p.x = x;
  p.y = y;
  return p;
}

std::vector<std::uint16_t> Ids(const std::vector<core::Position>& positions) {
  std::vector<std::uint16_t> ids;
  for (const core::Position& p : positions) ids.push_back(p.robot_id);
  return ids;
}

RadioParams Range(double range_m, int hops = 1, double loss = 0.0) {
  RadioParams p;
  p.range_m = range_m;
  p.hops = hops;
  p.loss = loss;
  return p;
}

const core::Pose2 kSelf{{1.0, 5.0}, core::Angle(0)};

TEST(HeardRoundTest, HearsTheFreshRobotsInRangeAsAnnounced) {
  HeardRound heard(0, Range(1.0), WorldParams(), 0.5, 1);
  EXPECT_TRUE(heard.Hear(At(1, 1.9f, 5.0f), 10.0));
  EXPECT_FALSE(heard.Hear(At(1, 1.8f, 5.0f), 10.1));  // known already; the newest is kept
  EXPECT_TRUE(heard.Hear(At(2, 3.0f, 5.0f), 10.1));   // out of range
  EXPECT_FALSE(heard.Hear(At(0, 4.0f, 5.0f), 10.1));  // its own announcement
  core::Round round;
  heard.Assemble(7, 10.2, kSelf, {0.5, 0.0}, &round);
  EXPECT_EQ(round.tick, 7u);
  EXPECT_FLOAT_EQ(round.pose.x, 1.0f);
  EXPECT_FLOAT_EQ(round.pose.linear_velocity, 0.5f);
  ASSERT_EQ(Ids(round.robots), std::vector<std::uint16_t>({1}));
  EXPECT_FLOAT_EQ(round.robots[0].x, 1.8f);
  EXPECT_TRUE(round.relayed.empty());
  EXPECT_EQ(heard.known(), (std::set<std::uint16_t>{0, 1, 2}));
  // Delivered: robot 1's latest position arrived 0.1 s before the round.
  EXPECT_EQ(heard.Delivered(round, 10.2, 0.11), std::make_pair(std::size_t{1}, std::size_t{1}));
  EXPECT_EQ(heard.Delivered(round, 10.2, 0.05), std::make_pair(std::size_t{1}, std::size_t{0}));
  // Robot 1 falls silent: after the timeout it is heard no more.
  heard.Assemble(8, 10.61, kSelf, {}, &round);
  EXPECT_TRUE(round.robots.empty());
}

TEST(HeardRoundTest, RelaysHopByHopAndGivesMissionPeersWhereverTheyAre) {
  HeardRound heard(0, Range(1.0, 3), WorldParams(), 1.0, 1);
  heard.Hear(At(1, 1.9f, 5.0f), 0.0);
  heard.Hear(At(2, 2.8f, 5.0f), 0.0);
  heard.Hear(At(3, 3.7f, 5.0f), 0.0);
  heard.Hear(At(4, 4.6f, 5.0f), 0.0);  // four hops away
  heard.Hear(At(5, 9.0f, 9.0f), 0.0);  // far
  core::Round round;
  heard.Assemble(1, 0.1, kSelf, {}, &round);
  EXPECT_EQ(Ids(round.robots), std::vector<std::uint16_t>({1}));
  EXPECT_EQ(Ids(round.relayed), std::vector<std::uint16_t>({2, 3}));
  EXPECT_TRUE(round.mission_peers.empty());
  core::MissionSpec order;
  order.id = 7;
  order.robot_ids = {0, 5};
  heard.Take(order);
  heard.Assemble(2, 0.2, kSelf, {}, &round);
  EXPECT_EQ(Ids(round.mission_peers), std::vector<std::uint16_t>({5}));
  heard.Take(core::ObjectDelete{7});
  heard.Assemble(3, 0.3, kSelf, {}, &round);
  EXPECT_TRUE(round.mission_peers.empty());
}

TEST(HeardRoundTest, LosesWhatTheRadioLosesAndCountsOutsideTheArenaAtItsEdge) {
  HeardRound lossless(0, Range(1.0), WorldParams(), 1.0, 1);
  HeardRound lossy(0, Range(1.0, 1, 1.0), WorldParams(), 1.0, 1);
  for (HeardRound* h : {&lossless, &lossy}) h->Hear(At(1, 1.5f, 5.0f), 0.0);
  core::Round round;
  lossy.Assemble(1, 0.0, kSelf, {}, &round);
  EXPECT_TRUE(round.robots.empty());
  // A robot announced just outside the arena is tested at its edge, carried as announced.
  const core::Pose2 edge{{0.3, 5.0}, core::Angle(0)};
  lossless.Hear(At(2, -0.5f, 5.0f), 0.0);
  lossless.Assemble(1, 0.0, edge, {}, &round);
  ASSERT_EQ(Ids(round.robots), std::vector<std::uint16_t>({2}));  // robot 1 is 1.2 m away
  EXPECT_FLOAT_EQ(round.robots[0].x, -0.5f);
}

}  // namespace
}  // namespace sim
}  // namespace swarm_transport
