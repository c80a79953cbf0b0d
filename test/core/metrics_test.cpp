// Metrics [SPEC 8, T7]: swarm components, transport slip / distance / waits, leader success,
// and the statistics over runs, on hand-built positions.
#include "swarm_transport/core/metrics.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <vector>

namespace swarm_transport {
namespace core {
namespace {

using Points = std::vector<Vec2>;

TEST(SwarmComponentsTest, ChainWithinRangeIsOneSwarm) {
  // Each robot is 0.9 from the next: the ends are 3.6 apart, yet it is one chain [Fig. 7.1].
  const Points chain = {{1.0, 1.0}, {1.9, 1.0}, {2.8, 1.0}, {3.7, 1.0}, {4.6, 1.0}};
  const SwarmComponents swarms(chain, 1.0);
  EXPECT_EQ(swarms.SwarmCount(), 1u);
  EXPECT_EQ(swarms.LargestSwarm(), 5u);
  EXPECT_EQ(swarms.SizeOfSwarmOf(4), 5u);
}

TEST(SwarmComponentsTest, RangeIsInclusive) {
  const SwarmComponents touching({{0.0, 0.0}, {1.0, 0.0}}, 1.0);
  EXPECT_EQ(touching.SwarmCount(), 1u);
  const SwarmComponents apart({{0.0, 0.0}, {1.0001, 0.0}}, 1.0);
  EXPECT_EQ(apart.SwarmCount(), 2u);
}

TEST(SwarmComponentsTest, ThreeClustersAreThreeSwarms) {
  const Points robots = {{1.0, 1.0}, {8.0, 8.0}, {1.5, 1.2}, {5.0, 1.0},
                         {8.5, 8.3}, {1.2, 1.8}, {5.3, 1.4}, {8.1, 7.5}};
  const SwarmComponents swarms(robots, 1.0);
  ASSERT_EQ(swarms.SwarmCount(), 3u);
  // Numbered in the order of each swarm's lowest index.
  EXPECT_EQ(swarms.ComponentOf(0), 0u);
  EXPECT_EQ(swarms.ComponentOf(1), 1u);
  EXPECT_EQ(swarms.ComponentOf(3), 2u);
  EXPECT_EQ(swarms.ComponentOf(2), 0u);
  EXPECT_EQ(swarms.ComponentOf(5), 0u);
  EXPECT_EQ(swarms.ComponentOf(4), 1u);
  EXPECT_EQ(swarms.ComponentOf(7), 1u);
  EXPECT_EQ(swarms.ComponentOf(6), 2u);
  EXPECT_EQ(swarms.ComponentSize(0), 3u);
  EXPECT_EQ(swarms.ComponentSize(1), 3u);
  EXPECT_EQ(swarms.ComponentSize(2), 2u);
  EXPECT_EQ(swarms.LargestSwarm(), 3u);
}

TEST(SwarmComponentsTest, EmptyAndDegenerateInput) {
  const SwarmComponents none({}, 1.0);
  EXPECT_EQ(none.SwarmCount(), 0u);
  EXPECT_EQ(none.LargestSwarm(), 0u);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const SwarmComponents with_nan({{1.0, 1.0}, {nan, 1.0}, {1.1, 1.0}}, 1.0);
  EXPECT_EQ(with_nan.SwarmCount(), 2u);
  EXPECT_EQ(with_nan.SizeOfSwarmOf(1), 1u);
  const SwarmComponents no_range({{1.0, 1.0}, {1.0, 1.0}}, 0.0);
  EXPECT_EQ(no_range.SwarmCount(), 2u);
  const SwarmComponents far({{1e300, -1e300}, {-1e300, 1e300}, {1.0, 1.0}}, 1.0);
  EXPECT_EQ(far.SwarmCount(), 3u);
}

TEST(SwarmComponentsTest, GridMatchesAllPairsOnAThousandRobots) {
  // A deterministic scatter over the arena; the grid must agree with the plain O(n^2) graph.
  Points robots;
  std::uint64_t state = 12345;
  auto next = [&state]() {
    state = state * 6364136223846793005ULL + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) / static_cast<double>(1ULL << 53);
  };
  for (int i = 0; i < 1000; ++i) robots.push_back({next() * 11.0, next() * 11.0});
  const double range = 0.3;
  const SwarmComponents swarms(robots, range);
  for (std::size_t i = 0; i < robots.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (Distance(robots[i], robots[j]) <= range) {
        ASSERT_EQ(swarms.ComponentOf(i), swarms.ComponentOf(j)) << i << " " << j;
      }
    }
  }
  std::size_t total = 0;
  for (std::size_t c = 0; c < swarms.SwarmCount(); ++c) total += swarms.ComponentSize(c);
  EXPECT_EQ(total, robots.size());
  EXPECT_GT(swarms.SwarmCount(), 1u);
}

TEST(StatisticsTest, MeanAndMedian) {
  EXPECT_DOUBLE_EQ(Mean({1.0, 2.0, 6.0}), 3.0);
  EXPECT_DOUBLE_EQ(Median({5.0, 1.0, 3.0}), 3.0);
  EXPECT_DOUBLE_EQ(Median({4.0, 1.0, 3.0, 100.0}), 3.5);
  EXPECT_TRUE(std::isnan(Mean({})));
  EXPECT_TRUE(std::isnan(Median({})));
}

TEST(StatisticsTest, TrimmedMeanOfTenRunsAveragesTheMiddleSix) {
  // Outliers at both ends; the middle six (sorted) are 3..8, mean 5.5.
  const std::vector<double> runs = {8.0, -1000.0, 3.0, 5.0, 1000.0, 4.0, 7.0, 6.0, -50.0, 90.0};
  EXPECT_DOUBLE_EQ(TrimmedMean(runs, 6), 5.5);
  EXPECT_DOUBLE_EQ(TrimmedMean(runs), 5.5);
}

TEST(StatisticsTest, TrimmedMeanOfFifteenRuns) {
  // Sorted: -900, -800 | 1 | 2 .. 10 | 11 | 800, 900.
  const std::vector<double> runs = {900.0, 5.0, 1.0, 2.0, -900.0, 3.0,   4.0,   11.0,
                                    6.0,   7.0, 8.0, 9.0, 10.0,   800.0, -800.0};
  // Middle 11 [T7.3, T7.4]: 1 .. 11, mean 6.
  EXPECT_DOUBLE_EQ(TrimmedMean(runs, 11), 6.0);
  // Middle 9 [T7.3]: 2 .. 10, mean 6.
  EXPECT_DOUBLE_EQ(TrimmedMean(runs, 9), 6.0);
  EXPECT_DOUBLE_EQ(TrimmedMean(runs), 6.0);
  // A skewed middle shows the right count is kept: drop 2 (middle 11) vs 3 (middle 9).
  const std::vector<double> skewed = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 11, 100};
  EXPECT_DOUBLE_EQ(TrimmedMean(skewed, 11), 0.0);
  const std::vector<double> skewed2 = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 22, 44, 100, 100};
  EXPECT_DOUBLE_EQ(TrimmedMean(skewed2, 11), 66.0 / 11.0);
  EXPECT_DOUBLE_EQ(TrimmedMean(skewed2, 9), 22.0 / 9.0);
  // The default keeps the thesis's middle 11 of 15.
  EXPECT_DOUBLE_EQ(TrimmedMean(skewed2), 66.0 / 11.0);
}

TEST(StatisticsTest, TrimmedMeanSmallAndOddCases) {
  EXPECT_DOUBLE_EQ(TrimmedMean({1.0, 2.0, 9.0}), 4.0);            // n < 5: plain mean
  EXPECT_DOUBLE_EQ(TrimmedMean({1.0, 2.0, 9.0}, 0), 4.0);         // middle 0: plain mean
  EXPECT_DOUBLE_EQ(TrimmedMean({1.0, 2.0, 9.0}, 7), 4.0);         // middle >= n: plain mean
  EXPECT_DOUBLE_EQ(TrimmedMean({1.0, 2.0, 3.0, 100.0}, 1), 2.5);  // odd n - m keeps m + 1
  EXPECT_TRUE(std::isnan(TrimmedMean({})));
}

TEST(TransportTrackerTest, PureTranslationHasNoSlip) {
  TransportTracker t;
  const Points start = {{1.0, 1.0}, {1.2, 1.0}, {1.0, 1.3}};
  const std::vector<bool> leaders = {true, false, false};
  ASSERT_TRUE(t.Feed(10, start, leaders));
  Points p = start;
  for (std::uint64_t tick = 11; tick <= 14; ++tick) {
    for (Vec2& q : p) q = q + Vec2{0.06, 0.08};  // 0.1 per tick
    ASSERT_TRUE(t.Feed(tick, p, leaders));
  }
  EXPECT_EQ(t.ticks(), 4u);
  EXPECT_NEAR(t.SlipPerRobot(), 0.0, 1e-12);
  EXPECT_NEAR(t.DistancePerRobot(), 0.4, 1e-12);
  EXPECT_EQ(t.LeaderWaits(), 0u);
}

TEST(TransportTrackerTest, OneRobotMovingRelativeToTheOthers) {
  // Four robots; robot 3 moves 0.1 in x, the others stand. Centroid moves 0.025 in x.
  // Slip: robots 0-2 each |0 - 0.025| = 0.025, robot 3 |0.1 - 0.025| = 0.075; sum 0.15, mean
  // 0.0375. Distance: 0.1 / 4 = 0.025. Leader 0 stood: one wait.
  TransportTracker t;
  const Points a = {{1.0, 1.0}, {2.0, 1.0}, {1.0, 2.0}, {2.0, 2.0}};
  const std::vector<bool> leaders = {true, false, false, false};
  ASSERT_TRUE(t.Feed(0, a, leaders));
  Points b = a;
  b[3].x += 0.1;
  ASSERT_TRUE(t.Feed(1, b, leaders));
  EXPECT_EQ(t.ticks(), 1u);
  EXPECT_NEAR(t.SlipPerRobot(), 0.0375, 1e-12);
  EXPECT_NEAR(t.DistancePerRobot(), 0.025, 1e-12);
  EXPECT_EQ(t.LeaderWaits(), 1u);
  // Everyone translates by (0, 0.1) next: slip unchanged, distance + 0.1, no wait.
  Points c = b;
  for (Vec2& q : c) q.y += 0.1;
  ASSERT_TRUE(t.Feed(2, c, leaders));
  EXPECT_NEAR(t.SlipPerRobot(), 0.0375, 1e-12);
  EXPECT_NEAR(t.DistancePerRobot(), 0.125, 1e-12);
  EXPECT_EQ(t.LeaderWaits(), 1u);
}

TEST(TransportTrackerTest, LeaderWaitsCountEveryLeaderAndTick) {
  TransportTracker t;
  Points p = {{1.0, 1.0}, {2.0, 1.0}, {3.0, 1.0}};
  const std::vector<bool> leaders = {true, true, false};
  ASSERT_TRUE(t.Feed(0, p, leaders));
  p[2].x += 0.1;  // both leaders stand
  ASSERT_TRUE(t.Feed(1, p, leaders));
  p[0].x += 0.1;  // leader 1 stands
  p[2].x += 0.1;
  ASSERT_TRUE(t.Feed(2, p, leaders));
  p[0].x += 5e-7;  // below the threshold: both leaders wait
  p[1].x += 2e-6;  // above: leader 1 moved
  ASSERT_TRUE(t.Feed(3, p, leaders));
  EXPECT_EQ(t.LeaderWaits(), 4u);
}

TEST(TransportTrackerTest, LeaderContactCountsPassiveRobotTicksWithALeaderInRange) {
  // Range 1.0. Leader at x = 0; passive robots at x = 0.5 (in range), 1.0 (in range: the
  // boundary counts, as for the neighbourhood) and 3.0 (out of range).
  TransportTracker t(1.0);
  Points p = {{0.0, 0.0}, {0.5, 0.0}, {1.0, 0.0}, {3.0, 0.0}};
  const std::vector<bool> leaders = {true, false, false, false};
  ASSERT_TRUE(t.Feed(0, p, leaders));
  EXPECT_FALSE(t.LeaderContact().has_value());  // the start tick counts nothing
  ASSERT_TRUE(t.Feed(1, p, leaders));
  ASSERT_TRUE(t.LeaderContact().has_value());
  EXPECT_NEAR(*t.LeaderContact(), 2.0 / 3.0, 1e-12);
  // The far robot comes within range of the leader: 5 of 6 passive robot-ticks.
  p[3] = {0.0, 0.9};
  ASSERT_TRUE(t.Feed(2, p, leaders));
  EXPECT_NEAR(*t.LeaderContact(), 5.0 / 6.0, 1e-12);
  // A second leader does not count as a passive robot, nor twice for one in range of both.
  TransportTracker two(1.0);
  const Points q = {{0.0, 0.0}, {0.2, 0.0}, {0.1, 0.0}};
  ASSERT_TRUE(two.Feed(0, q, {true, true, false}));
  ASSERT_TRUE(two.Feed(1, q, {true, true, false}));
  EXPECT_DOUBLE_EQ(*two.LeaderContact(), 1.0);
}

TEST(TransportTrackerTest, LeaderContactIsUndefinedWithoutPassiveRobotsOrRange) {
  TransportTracker all_leaders(1.0);
  const Points p = {{0.0, 0.0}, {0.5, 0.0}};
  ASSERT_TRUE(all_leaders.Feed(0, p, {true, true}));
  ASSERT_TRUE(all_leaders.Feed(1, p, {true, true}));
  EXPECT_FALSE(all_leaders.LeaderContact().has_value());
  TransportTracker no_range;
  ASSERT_TRUE(no_range.Feed(0, p, {true, false}));
  ASSERT_TRUE(no_range.Feed(1, p, {true, false}));
  EXPECT_FALSE(no_range.LeaderContact().has_value());
}

TEST(TransportTrackerTest, RejectsCallsThatDoNotFit) {
  TransportTracker t;
  const std::vector<bool> two = {true, false};
  EXPECT_FALSE(t.Feed(0, {}, {}));
  EXPECT_FALSE(t.Feed(0, {{1.0, 1.0}}, two));
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(t.Feed(0, {{1.0, 1.0}, {nan, 1.0}}, two));
  EXPECT_FALSE(t.started());
  ASSERT_TRUE(t.Feed(5, {{1.0, 1.0}, {2.0, 1.0}}, two));
  EXPECT_FALSE(t.Feed(5, {{1.5, 1.0}, {2.0, 1.0}}, two));  // same tick
  EXPECT_FALSE(t.Feed(6, {{1.5, 1.0}, {2.0, 1.0}, {3.0, 1.0}}, {true, false, false}));
  // A missed tick: the movement since tick 5 counts, over two ticks.
  ASSERT_TRUE(t.Feed(7, {{1.1, 1.0}, {2.1, 1.0}}, two));
  EXPECT_EQ(t.ticks(), 2u);
  EXPECT_NEAR(t.DistancePerRobot(), 0.1, 1e-12);
  EXPECT_NEAR(t.SlipPerRobot(), 0.0, 1e-12);
}

TEST(LeaderTrackerTest, SwarmThatStaysAttachedGivesFullPath) {
  // The leader (index 0) drives from (1, 1) to (4, 1) in three ticks with two followers.
  LeaderTracker t({4.0, 1.0}, 1.0);
  for (std::uint64_t k = 0; k <= 3; ++k) {
    const double x = 1.0 + static_cast<double>(k);
    ASSERT_TRUE(t.Feed(k, {{x, 1.0}, {x - 0.5, 1.0}, {x - 0.9, 1.2}}, 0));
  }
  EXPECT_FALSE(t.lost_swarm());
  EXPECT_DOUBLE_EQ(t.PathFractionAttached(), 1.0);
  EXPECT_EQ(t.SwarmAtLastTick(), 2u);
  EXPECT_EQ(t.LeaderWaits(), 0u);
  EXPECT_EQ(t.ticks(), 3u);
  EXPECT_NEAR(t.DistanceToTarget(), 0.0, 1e-12);
}

TEST(LeaderTrackerTest, PathFractionWhenTheFirstRobotIsLost) {
  // Leader (index 1) from (1, 1) to target (9, 1): 8 m. Follower 0 keeps up, follower 2
  // stays at (1, 1). At x = 2 follower 2 is 1.0 away (still attached, inclusive range); at
  // x = 3 it is lost: the leader covered 2 of 8 m.
  LeaderTracker t({9.0, 1.0}, 1.0);
  ASSERT_TRUE(t.Feed(0, {{0.8, 1.0}, {1.0, 1.0}, {1.0, 1.0}}, 1));
  ASSERT_TRUE(t.Feed(1, {{1.8, 1.0}, {2.0, 1.0}, {1.0, 1.0}}, 1));
  EXPECT_FALSE(t.lost_swarm());
  ASSERT_TRUE(t.Feed(2, {{2.8, 1.0}, {3.0, 1.0}, {1.0, 1.0}}, 1));
  EXPECT_TRUE(t.lost_swarm());
  EXPECT_NEAR(t.PathFractionAttached(), 0.25, 1e-12);
  // The leader waits one tick, then goes on; the lost robot rejoining changes nothing.
  ASSERT_TRUE(t.Feed(3, {{2.8, 1.0}, {3.0, 1.0}, {2.5, 1.0}}, 1));
  ASSERT_TRUE(t.Feed(4, {{8.8, 1.0}, {9.0, 1.0}, {8.5, 1.0}}, 1));
  EXPECT_NEAR(t.PathFractionAttached(), 0.25, 1e-12);
  EXPECT_EQ(t.SwarmAtLastTick(), 2u);
  EXPECT_EQ(t.LeaderWaits(), 1u);
}

TEST(LeaderTrackerTest, SwarmAtArrivalExcludesTheLeaderAndTheLost) {
  LeaderTracker t({5.0, 5.0}, 1.0);
  ASSERT_TRUE(t.Feed(0, {{1.0, 1.0}, {1.5, 1.0}, {1.0, 1.5}, {1.5, 1.5}}, 0));
  EXPECT_EQ(t.SwarmAtLastTick(), 3u);
  ASSERT_TRUE(t.Feed(1, {{5.0, 5.0}, {4.5, 5.0}, {1.0, 1.5}, {1.5, 1.5}}, 0));
  EXPECT_EQ(t.SwarmAtLastTick(), 1u);
  EXPECT_TRUE(t.lost_swarm());
  EXPECT_DOUBLE_EQ(t.PathFractionAttached(), 1.0);  // lost only at the target itself
}

TEST(LeaderTrackerTest, SplitAtTheStartGivesZeroAndBadCallsAreRejected) {
  LeaderTracker t({5.0, 1.0}, 1.0);
  EXPECT_FALSE(t.Feed(0, {{1.0, 1.0}}, 1));  // leader index out of range
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(t.Feed(0, {{nan, 1.0}}, 0));
  ASSERT_TRUE(t.Feed(3, {{1.0, 1.0}, {4.0, 4.0}}, 0));
  EXPECT_TRUE(t.lost_swarm());
  EXPECT_DOUBLE_EQ(t.PathFractionAttached(), 0.0);
  EXPECT_EQ(t.SwarmAtLastTick(), 0u);
  EXPECT_FALSE(t.Feed(3, {{1.1, 1.0}, {4.0, 4.0}}, 0));  // same tick
}

TEST(DispersionTest, CoverageAndNearestNeighbourSpread) {
  // A 10 x 10 m arena on 1 m cells; one robot at (0.5, 0.5) covering 0.6 m: only its own cell.
  Dispersion one = DispersionOf({{0.5, 0.5}}, 10.0, 0.6, 1.0);
  EXPECT_DOUBLE_EQ(one.coverage_fraction, 0.01);
  EXPECT_TRUE(std::isnan(one.nn_mean_m));
  // Covering 1.0 m it reaches the centres of the cells right of and above it too.
  EXPECT_DOUBLE_EQ(DispersionOf({{0.5, 0.5}}, 10.0, 1.0, 1.0).coverage_fraction, 0.03);
  // Evenly spaced: nearest neighbours all 2 m, no spread.
  const Dispersion even = DispersionOf({{1.0, 1.0}, {3.0, 1.0}, {5.0, 1.0}}, 10.0, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(even.nn_mean_m, 2.0);
  EXPECT_DOUBLE_EQ(even.nn_cv, 0.0);
  // Two close, one far: nearest distances 1, 1, 4 -> mean 2, std sqrt(2), cv sqrt(2) / 2.
  const Dispersion uneven = DispersionOf({{1.0, 1.0}, {2.0, 1.0}, {6.0, 1.0}}, 10.0, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(uneven.nn_mean_m, 2.0);
  EXPECT_NEAR(uneven.nn_cv, std::sqrt(2.0) / 2.0, 1e-12);
  // Non-finite positions are left out; two robots in the same cell cover it once.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_DOUBLE_EQ(
      DispersionOf({{0.5, 0.5}, {0.5, 0.5}, {nan, 1.0}}, 10.0, 0.6, 1.0).coverage_fraction, 0.01);
}

// The all-pairs nearest-neighbour search the k-d tree replaced (DispersionOf before issue 25).
std::vector<double> AllPairsNearest(const Points& at) {
  std::vector<double> nearest(at.size(), std::numeric_limits<double>::infinity());
  for (std::size_t i = 0; i < at.size(); ++i) {
    for (std::size_t j = i + 1; j < at.size(); ++j) {
      const double gap = Distance(at[i], at[j]);
      nearest[i] = std::min(nearest[i], gap);
      nearest[j] = std::min(nearest[j], gap);
    }
  }
  return nearest;
}

// Random crowds of every shape the tree must take: uniform, clustered (many robots in one
// spot, duplicates), on a line, a grid of exact ties, huge and tiny coordinates.
std::vector<Points> RandomCrowds() {
  std::mt19937_64 rng(2025);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Points> crowds;
  for (int n : {0, 1, 2, 3, 9, 17, 100, 1000, 3000}) {
    Points uniform;
    for (int i = 0; i < n; ++i) uniform.push_back({unit(rng) * 50.0, unit(rng) * 50.0});
    crowds.push_back(uniform);
  }
  Points clustered;
  for (int i = 0; i < 2000; ++i) {
    if (i % 3 == 0) {
      clustered.push_back({unit(rng) * 100.0, unit(rng) * 100.0});
    } else if (i % 3 == 1) {
      clustered.push_back({5.0 + unit(rng) * 1e-6, 5.0 + unit(rng) * 1e-6});
    } else {
      clustered.push_back({70.0, 30.0 + (i % 7) * 0.25});  // duplicates
    }
  }
  crowds.push_back(clustered);
  Points line, grid, wide, same;
  for (int i = 0; i < 500; ++i) line.push_back({unit(rng) * 10.0, 3.0});
  for (int i = 0; i < 40; ++i) {
    for (int j = 0; j < 40; ++j) grid.push_back({i * 0.1, j * 0.1});  // every spacing ties
  }
  for (int i = 0; i < 500; ++i) {
    const double scale = i % 2 ? 1e150 : 1e-150;
    wide.push_back({(unit(rng) - 0.5) * scale, (unit(rng) - 0.5) * scale});
  }
  for (int i = 0; i < 300; ++i) same.push_back({1.5, -2.5});
  for (const Points* p : {&line, &grid, &wide, &same}) crowds.push_back(*p);
  return crowds;
}

TEST(NearestNeighbourTest, TreeIsBitIdenticalToAllPairsOnRandomCrowds) {
  for (const Points& crowd : RandomCrowds()) {
    const std::vector<double> tree = NearestNeighbourDistances(crowd);
    const std::vector<double> brute = AllPairsNearest(crowd);
    ASSERT_EQ(tree.size(), brute.size());
    for (std::size_t i = 0; i < tree.size(); ++i) {
      // Bit for bit (EXPECT_EQ on doubles is exact; +inf equals +inf).
      ASSERT_EQ(tree[i], brute[i]) << "robot " << i << " of " << crowd.size();
    }
  }
}

TEST(NearestNeighbourTest, DispersionOfARandomCrowdMatchesTheAllPairsFormula) {
  // DispersionOf's nearest-neighbour mean and CV, computed as before issue 25.
  for (const Points& crowd : RandomCrowds()) {
    const std::vector<double> nearest = AllPairsNearest(crowd);
    const Dispersion d = DispersionOf(crowd, 50.0, 1.0, 0.5);
    if (crowd.size() < 2) {
      EXPECT_TRUE(std::isnan(d.nn_mean_m));
      continue;
    }
    const double mean = Mean(nearest);
    double squares = 0.0;
    for (const double v : nearest) squares += (v - mean) * (v - mean);
    const double cv = mean > 0.0 ? std::sqrt(squares / static_cast<double>(nearest.size())) / mean
                                 : std::numeric_limits<double>::quiet_NaN();
    EXPECT_EQ(d.nn_mean_m, mean) << crowd.size();
    if (std::isnan(cv)) {
      EXPECT_TRUE(std::isnan(d.nn_cv));
    } else {
      EXPECT_EQ(d.nn_cv, cv) << crowd.size();
    }
  }
}

TEST(TransportTrackerTest, LeaderContactMatchesEveryPairOnARandomCrowd) {
  // The contact count looks at the leaders only; it is the count over all pairs.
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  const double range = 1.0;
  TransportTracker t(range);
  std::uint64_t passive = 0, contact = 0;
  std::vector<bool> leaders(600);
  for (std::size_t i = 0; i < leaders.size(); ++i) leaders[i] = i % 37 == 0;
  for (std::uint64_t tick = 0; tick < 5; ++tick) {
    Points p;
    for (std::size_t i = 0; i < leaders.size(); ++i) {
      p.push_back({unit(rng) * 20.0, unit(rng) * 20.0});
    }
    ASSERT_TRUE(t.Feed(tick, p, leaders));
    if (tick == 0) continue;
    for (std::size_t i = 0; i < p.size(); ++i) {
      if (leaders[i]) continue;
      ++passive;
      for (std::size_t j = 0; j < p.size(); ++j) {
        if (leaders[j] && !FartherThan(p[i], p[j], range)) {
          ++contact;
          break;
        }
      }
    }
  }
  ASSERT_TRUE(t.LeaderContact().has_value());
  EXPECT_GT(contact, 0u);
  EXPECT_EQ(*t.LeaderContact(), static_cast<double>(contact) / static_cast<double>(passive));
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
