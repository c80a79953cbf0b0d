#include "swarm_transport/core/tick_stats.h"

#include <gtest/gtest.h>

namespace swarm_transport {
namespace core {
namespace {

TEST(TickStatsTest, RealtimeTickIsLateOnlyMoreThanTenPercentOverThePeriod) {
  TickStats s(0.1, true);
  s.OnTick(10.0);
  s.OnTick(10.109);  // 9% over: on time
  s.OnTick(10.221);  // 12% over: late
  s.OnTick(10.300);
  EXPECT_EQ(s.ticks(), 4u);
  EXPECT_EQ(s.late_ticks(), 1u);
  EXPECT_NEAR(s.max_period_s(), 0.112, 1e-9);
  EXPECT_DOUBLE_EQ(s.first_tick_s(), 10.0);
}

TEST(TickStatsTest, LockstepMissedRoundsAreLateTicks) {
  TickStats s(0.1, false);
  s.OnRound(0, 0.0, 100.0);
  s.OnRound(1, 0.1, 100.001);
  s.OnRound(4, 0.4, 100.002);  // rounds 2 and 3 never arrived
  EXPECT_EQ(s.rounds(), 3u);
  EXPECT_EQ(s.missed_rounds(), 2u);
  EXPECT_EQ(s.late_ticks(), 2u);
  // Lock-step time is simulated: the wall gap says nothing, a received round is fresh.
  EXPECT_TRUE(s.RoundFresh(500.0));
}

TEST(TickStatsTest, RealtimeRoundIsFreshWithinOneTickOfArrivalAndLatency) {
  TickStats s(0.1, true);
  EXPECT_FALSE(s.RoundFresh(0.0));
  s.OnRound(0, 0.0, 50.001);  // the fastest delivery so far: latency 0 by definition
  EXPECT_TRUE(s.RoundFresh(50.101));
  EXPECT_FALSE(s.RoundFresh(50.112));  // more than 1.1 periods after it arrived
  s.OnRound(1, 0.1, 50.251);           // 150 ms after it was sampled (relative to the fastest)
  EXPECT_NEAR(s.max_latency_s(), 0.15, 1e-9);
  EXPECT_FALSE(s.RoundFresh(50.252));
  s.OnRound(2, 0.2, 50.202);  // on time again
  EXPECT_TRUE(s.RoundFresh(50.210));
}

TEST(TickStatsTest, DeliveredNeverExceedsExpectedAndLineHasEveryField) {
  TickStats s(0.1, true);
  s.OnTick(1.0);
  s.OnTick(1.3);
  s.CountUpdates(5, 4);
  s.CountUpdates(2, 3);
  EXPECT_EQ(s.updates(), 7u);
  EXPECT_EQ(s.delivered(), 6u);
  const std::string line = s.TakeLine();
  for (const char* key :
       {"ticks=2 ", "late=1 ", "max_period_ms=300.000 ", "rounds=0 ", "missed_rounds=0 ",
        "updates=7 ", "delivered=6 ", "max_latency_ms=", "first_tick_wall=1.000000"}) {
    EXPECT_NE(line.find(key), std::string::npos) << key << " in " << line;
  }
  // Maxima cover the time since the last line.
  EXPECT_EQ(s.max_period_s(), 0.0);
  EXPECT_EQ(s.ticks(), 2u);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
