#include "swarm_transport/sim/radio.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

namespace swarm_transport {
namespace sim {
namespace {

using Indices = std::vector<std::size_t>;

// Robots at (x, 5) with ids 0.., heading 0: a line of robots along x.
World2D Line(const std::vector<double>& xs) {
  World2D world{WorldParams()};
  std::string error;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    EXPECT_TRUE(world.Spawn(static_cast<std::uint16_t>(i), {{xs[i], 5.0}, core::Angle(0)}, &error))
        << error;
  }
  return world;
}

RadioParams Range(double range_m, int hops = 1) {
  RadioParams p;
  p.range_m = range_m;
  p.hops = hops;
  return p;
}

RadioRound HearOne(Radio* radio, std::size_t i) {
  RadioRound round;
  radio->Hear(i, &round);
  return round;
}

TEST(RadioTest, HearsTheRobotsInRangeOnly) {
  const World2D world = Line({1.0, 1.9, 3.05, 4.0});
  core::Rng rng(1, 0);
  Radio radio(Range(1.0), &rng);
  radio.Begin(world, {}, {});
  EXPECT_EQ(HearOne(&radio, 0).in_range, (Indices{1}));
  EXPECT_EQ(HearOne(&radio, 1).in_range, (Indices{0}));  // 1.15 to robot 2
  EXPECT_EQ(HearOne(&radio, 2).in_range, (Indices{3}));
  EXPECT_TRUE(HearOne(&radio, 0).chain.empty());  // one hop: no chain
}

TEST(RadioTest, AChainPassesOnWhatItsRobotsHeardUpToTheHopLimit) {
  // 0.9 apart at range 1.0: one swarm; a gap of 1.1 splits it (issue 9's test case).
  const World2D world = Line({1.0, 1.9, 2.8, 3.7, 4.8});
  core::Rng rng(1, 0);
  Radio chain(Range(1.0, 16), &rng);
  chain.Begin(world, {}, {});
  const RadioRound first = HearOne(&chain, 0);
  EXPECT_EQ(first.in_range, (Indices{1}));
  EXPECT_EQ(first.chain, (Indices{2, 3}));            // robot 4 is beyond the gap
  EXPECT_EQ(HearOne(&chain, 2).chain, (Indices{0}));  // 1 and 3 in range; 4 not linked
  Radio two_hops(Range(1.0, 2), &rng);
  two_hops.Begin(world, {}, {});
  EXPECT_EQ(HearOne(&two_hops, 0).chain, (Indices{2}));
}

TEST(RadioTest, CopiesStandOnTheirOwnerAndStatistsAreHeardEverywhere) {
  const World2D world = Line({1.0, 1.5, 6.0});
  RadioExtra copy_of_1;
  copy_of_1.virtual_copy = true;
  copy_of_1.owner = 1;
  copy_of_1.position = {9.0, 9.0};  // announced far away: relayed at robot 1's pose
  RadioExtra copy_of_2;
  copy_of_2.virtual_copy = true;
  copy_of_2.owner = 2;
  RadioExtra statist;
  statist.position = {10.0, 10.0};
  core::Rng rng(1, 0);
  Radio radio(Range(1.0), &rng);
  radio.Begin(world, {copy_of_1, copy_of_2, statist}, {});
  EXPECT_EQ(radio.extra_owner(), (std::vector<long>{1, 2, -1}));
  EXPECT_EQ(HearOne(&radio, 0).extras, (Indices{0, 2}));  // robot 2's copy is out of range
  EXPECT_EQ(HearOne(&radio, 1).extras, (Indices{2}));     // not its own copy
  EXPECT_EQ(HearOne(&radio, 2).extras, (Indices{2}));
}

TEST(RadioTest, MissionPeersAreHeardWhereverTheyAreAndOnlyOnce) {
  const World2D world = Line({1.0, 1.5, 6.0, 9.0});
  LiveMissions missions;
  missions[4].members = {0, 1, 2, 7};  // 7 is not in the world
  missions[9].members = {0, 3};
  core::Rng rng(1, 0);
  Radio radio(Range(1.0), &rng);
  radio.Begin(world, {}, missions);
  const RadioRound first = HearOne(&radio, 0);
  EXPECT_EQ(first.in_range, (Indices{1}));
  EXPECT_EQ(first.peers, (Indices{2, 3}));  // 1 is heard in range already
  EXPECT_EQ(HearOne(&radio, 2).peers, (Indices{0, 1}));
  EXPECT_TRUE(HearOne(&radio, 3).peers.size() == 1);
}

TEST(RadioTest, LossDropsPositionsButNotTheMissionChannel) {
  const World2D world = Line({1.0, 1.5, 2.0});
  LiveMissions missions;
  missions[1].members = {0, 1};
  RadioParams p = Range(1.0);
  p.loss = 1.0;
  core::Rng rng(1, 0);
  Radio radio(p, &rng);
  radio.Begin(world, {}, missions);
  const RadioRound round = HearOne(&radio, 0);
  EXPECT_TRUE(round.in_range.empty());
  EXPECT_EQ(round.peers, (Indices{1}));  // a lost neighbour still reaches it as a peer
  // Over a chain too: a member whose position the chain lost is heard as a peer (issue 29: it
  // was not, and a burst of radio loss made members lose their first leader, promote another
  // and stall the mission in TRANSPORT with two first leaders).
  RadioParams chain = Range(1.0, 16);
  chain.loss = 1.0;
  missions[1].members = {0, 1, 2};
  core::Rng lossy(1, 0);
  Radio over_chain(chain, &lossy);
  over_chain.Begin(world, {}, missions);
  for (std::size_t i = 0; i < 3; ++i) {
    const RadioRound r = HearOne(&over_chain, i);
    EXPECT_TRUE(r.in_range.empty() && r.chain.empty());
    EXPECT_EQ(r.peers.size(), 2u) << "robot " << i;
  }
  // The same seed loses the same positions.
  p.loss = 0.5;
  core::Rng a(7, 3), b(7, 3);
  Radio ra(p, &a), rb(p, &b);
  ra.Begin(world, {}, {});
  rb.Begin(world, {}, {});
  for (std::size_t i = 0; i < 3; ++i) EXPECT_EQ(HearOne(&ra, i).in_range, HearOne(&rb, i).in_range);
}

TEST(RadioTest, AQuietRobotIsHeardByNobodyButHearsTheOthers) {
  // Robot 1 (dead or hung: it does not answer its ticks) stands between 0 and 2.
  const World2D world = Line({1.0, 1.9, 2.8, 6.0});
  LiveMissions missions;
  missions[4].members = {0, 1, 3};
  core::Rng rng(1, 0);
  Radio radio(Range(1.0, 16), &rng);
  radio.Begin(world, {}, missions, {1});
  const RadioRound first = HearOne(&radio, 0);
  EXPECT_TRUE(first.in_range.empty());  // not 1; 2 is beyond range without 1 to relay it
  EXPECT_TRUE(first.chain.empty());
  EXPECT_EQ(first.peers, (Indices{3}));                     // not 1 over the mission channel either
  EXPECT_EQ(HearOne(&radio, 1).in_range, (Indices{0, 2}));  // it still hears
  EXPECT_EQ(HearOne(&radio, 3).peers, (Indices{0}));
}

}  // namespace
}  // namespace sim
}  // namespace swarm_transport
