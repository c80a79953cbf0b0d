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
  // Lock-step time is simulated: the wall gap says nothing, a round comes with its tick.
  EXPECT_EQ(s.OnRound(4, 0.4, 500.0), 0.0);  // rounds 2 and 3 never arrived
  EXPECT_EQ(s.last_gap(), 2u);
  EXPECT_EQ(s.rounds(), 3u);
  EXPECT_EQ(s.missed_rounds(), 2u);
  EXPECT_EQ(s.late_ticks(), 2u);
}

TEST(TickStatsTest, RealtimeLatencyIsTheExcessOverTheFastestDelivery) {
  TickStats s(0.1, true);
  EXPECT_EQ(s.OnRound(0, 0.0, 50.002), 0.0);  // the only delivery yet: latency 0 by definition
  EXPECT_NEAR(s.OnRound(1, 0.1, 50.252), 0.15, 1e-9);  // 150 ms slower than the first
  EXPECT_NEAR(s.max_latency_s(), 0.15, 1e-9);
  EXPECT_EQ(s.last_gap(), 0u);
  EXPECT_EQ(s.OnRound(2, 0.2, 50.201), 0.0);  // faster than all before: the new reference
  EXPECT_NEAR(s.OnRound(3, 0.3, 50.303), 0.002, 1e-9);
  EXPECT_EQ(s.late_ticks(), 0u);  // real time: lateness is measured at the ticks
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
