#include "swarm_transport/sim/lockstep_barrier.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace swarm_transport {
namespace sim {
namespace {

using Answer = LockstepBarrier::Answer;

core::Velocity Forward(double linear) {
  core::Velocity v;
  v.linear = linear;
  return v;
}

// Two live robots, tick `tick` asked.
LockstepBarrier TwoLive(std::uint64_t tick = 1) {
  LockstepBarrier b;
  for (std::uint16_t id : {3, 7}) {
    b.Add(id);
    b.MakeLive(id);
  }
  b.StartTick(tick);
  b.Ask(3);
  b.Ask(7);
  return b;
}

// The answer names its tick and carries everything the robot sends in it: the tick closes on
// the answers alone. (Before issue 10's item 4 a robot announced in a separate tick_done how
// many mission messages it had sent on other topics, counted per publishing node; three races
// of that protocol were fixed in a95f00d and cannot occur any more.)
TEST(LockstepBarrierTest, ATickIsCompleteWhenEveryLiveRobotAnswered) {
  LockstepBarrier b = TwoLive();
  EXPECT_FALSE(b.AllAnswered());
  EXPECT_EQ(b.OnAnswer(3, 1, Forward(0.1)), Answer::kAnswer);
  EXPECT_FALSE(b.AllAnswered());
  EXPECT_EQ(b.Late(), (std::vector<std::uint16_t>{7}));
  EXPECT_EQ(b.OnAnswer(7, 1, Forward(0.2)), Answer::kAnswer);
  EXPECT_TRUE(b.AllAnswered());
  EXPECT_TRUE(b.Late().empty());
  EXPECT_DOUBLE_EQ(b.CommandOf(3).linear, 0.1);
  EXPECT_DOUBLE_EQ(b.CommandOf(7).linear, 0.2);
  // A second answer in the same tick, or one to a later tick, was not asked for.
  EXPECT_EQ(b.OnAnswer(7, 1, Forward(0.3)), Answer::kUnsolicited);
  EXPECT_EQ(b.OnAnswer(7, 2, Forward(0.3)), Answer::kUnsolicited);
  EXPECT_DOUBLE_EQ(b.CommandOf(7).linear, 0.2);
}

TEST(LockstepBarrierTest, ARobotThatIsNotLiveIsOutsideTheBarrier) {
  LockstepBarrier b;
  b.Add(1);
  b.StartTick(1);
  b.Ask(1);  // not live: not asked
  EXPECT_TRUE(b.AllAnswered());
  EXPECT_EQ(b.OnAnswer(1, 1, Forward(0.1)), Answer::kOutside);
  EXPECT_EQ(b.OnAnswer(99, 1, Forward(0.1)), Answer::kOutside);  // unknown
}

TEST(LockstepBarrierTest, ALateAnswerIsIgnoredAndTheRobotStands) {
  LockstepBarrier b = TwoLive(1);
  b.OnAnswer(3, 1, Forward(0.1));
  // Robot 7 misses tick 1 (the simulator gave up waiting); tick 2 asks both again.
  b.StartTick(2);
  b.Ask(3);
  b.Ask(7);
  EXPECT_DOUBLE_EQ(b.CommandOf(7).linear, 0.0);               // not answered yet: it would stand
  EXPECT_EQ(b.OnAnswer(7, 1, Forward(0.5)), Answer::kStale);  // its answer to tick 1
  EXPECT_FALSE(b.AllAnswered());
  EXPECT_DOUBLE_EQ(b.CommandOf(7).linear, 0.0);
  EXPECT_EQ(b.OnAnswer(7, 2, Forward(0.6)), Answer::kAnswer);
  EXPECT_DOUBLE_EQ(b.CommandOf(7).linear, 0.6);
}

TEST(LockstepBarrierTest, ARobotThatMissedAPerceptionAnswersTheNextTickAsUsual) {
  // Its Neighbors of tick 1 was lost: it never answers tick 1, and its answer to tick 2 counts
  // for tick 2 (the tick it names; no resynchronisation of counters).
  LockstepBarrier b = TwoLive(1);
  b.OnAnswer(3, 1, Forward(0.1));
  EXPECT_EQ(b.Late(), (std::vector<std::uint16_t>{7}));
  b.StartTick(2);
  b.Ask(3);
  b.Ask(3);  // asked twice within a tick: still one answer owed
  b.Ask(7);
  EXPECT_EQ(b.OnAnswer(7, 2, Forward(0.2)), Answer::kAnswer);
  EXPECT_EQ(b.OnAnswer(3, 2, Forward(0.2)), Answer::kAnswer);
  EXPECT_TRUE(b.AllAnswered());
}

TEST(LockstepBarrierTest, RemovingOrDisconnectingARobotItWaitsForEndsTheWait) {
  LockstepBarrier b = TwoLive(1);
  b.OnAnswer(3, 1, Forward(0.1));
  EXPECT_FALSE(b.AllAnswered());
  b.Remove(7);
  EXPECT_TRUE(b.AllAnswered());
  EXPECT_FALSE(b.Has(7));

  LockstepBarrier c = TwoLive(1);
  c.MakeNotLive(3);
  c.MakeNotLive(3);  // twice: counted once
  EXPECT_FALSE(c.AllAnswered());
  EXPECT_EQ(c.OnAnswer(3, 1, Forward(0.1)), Answer::kOutside);
  c.OnAnswer(7, 1, Forward(0.1));
  EXPECT_TRUE(c.AllAnswered());
}

// Race fixed in a95f00d: a tick waits for the dispatcher's stamped LOADED once LOADING was
// relayed, unless it arrived already; giving up names what it stops waiting for.
TEST(LockstepBarrierTest, HoldsForAwaitedDispatcherEvents) {
  LockstepBarrier b;
  EXPECT_FALSE(b.EventsAwaited());
  b.Await({4, 1});
  EXPECT_TRUE(b.EventsAwaited());
  b.Seen({4, 1});
  EXPECT_FALSE(b.EventsAwaited());
  b.Await({4, 1});  // the same event again (a repeated status): it arrived already
  EXPECT_FALSE(b.EventsAwaited());
  b.Await({4, 2});
  EXPECT_EQ(b.GiveUpEvents(), (std::vector<LockstepBarrier::EventKey>{{4, 2}}));
  EXPECT_FALSE(b.EventsAwaited());
  // The mission ends: its id may come back with events of its own.
  b.Forget(4);
  b.Await({4, 1});
  EXPECT_TRUE(b.EventsAwaited());
}

// A relayed phase status owes the dispatcher's event only when the dispatcher sends it on its
// own (a delay >= 0); an ended mission releases what was owed for it.
TEST(LockstepBarrierTest, PhaseStatusesOweTheDispatchersEvents) {
  using swarm_transport::core::MissionPhase;
  LockstepBarrier b;
  b.OnPhase(4, MissionPhase::kGathering, true, true);
  EXPECT_FALSE(b.EventsAwaited());
  b.OnPhase(4, MissionPhase::kLoading, false, true);  // LOADED by hand: not waited for
  EXPECT_FALSE(b.EventsAwaited());
  b.OnPhase(4, MissionPhase::kLoading, true, true);
  EXPECT_TRUE(b.EventsAwaited());
  b.Seen({4, 1});
  EXPECT_FALSE(b.EventsAwaited());
  b.OnPhase(4, MissionPhase::kUnloading, true, false);
  EXPECT_FALSE(b.EventsAwaited());
  b.OnPhase(4, MissionPhase::kUnloading, true, true);
  EXPECT_TRUE(b.EventsAwaited());
  b.OnPhase(4, MissionPhase::kAborted, true, true);
  EXPECT_FALSE(b.EventsAwaited());
  // Forgotten: LOADED of the id's next mission is owed again although the old one was seen.
  b.OnPhase(4, MissionPhase::kLoading, true, true);
  EXPECT_TRUE(b.EventsAwaited());
}

// Missions at a defined tick (issue 10, item 4): with a dispatcher, tick 1 waits for its
// schedule, and each scheduled order's start tick waits until the order arrived, whichever of
// the two topics delivers first.
TEST(LockstepBarrierTest, HoldsTicksForTheDispatchersScheduledOrders) {
  LockstepBarrier b;
  EXPECT_FALSE(b.OrdersMissing(1));  // no dispatcher expected
  b.ExpectSchedule();
  EXPECT_FALSE(b.OrdersMissing(0));  // tick 0 runs: the dispatcher schedules at tick 0
  EXPECT_TRUE(b.OrdersMissing(1));
  b.OrderArrived(7);  // the order overtook the schedule
  b.OnSchedule({{7, 10}, {8, 10}, {9, 30}});
  EXPECT_FALSE(b.OrdersMissing(1));
  EXPECT_FALSE(b.OrdersMissing(9));
  EXPECT_TRUE(b.OrdersMissing(10));  // 8 is due
  b.OrderArrived(8);
  EXPECT_FALSE(b.OrdersMissing(10));
  EXPECT_FALSE(b.OrdersMissing(29));
  EXPECT_TRUE(b.OrdersMissing(30));
  EXPECT_EQ(b.GiveUpOrders(30), (std::vector<std::uint16_t>{9}));
  EXPECT_FALSE(b.OrdersMissing(31));
  b.OrderArrived(12);  // a raw order nobody scheduled: nothing to wait for
  EXPECT_FALSE(b.OrdersMissing(40));
}

// Statist as dispatcher (SPEC 9.4): while a mission recruits, each tick after its statist's
// first waits until the dispatcher watched the previous tick's positions; its order, scheduled
// for the next tick, is waited for whichever topic delivers first.
TEST(LockstepBarrierTest, HoldsTicksWhileAMissionRecruits) {
  LockstepBarrier b;
  b.ExpectSchedule();
  b.OnSchedule({});
  b.OnRecruits(0, {{5, 20}});
  EXPECT_FALSE(b.RecruitsUnchecked(20));  // the statist stands from tick 20
  EXPECT_TRUE(b.RecruitsUnchecked(21));   // the dispatcher has not watched tick 20
  b.OnRecruits(20, {{5, 20}});
  EXPECT_FALSE(b.RecruitsUnchecked(21));
  EXPECT_TRUE(b.RecruitsUnchecked(22));
  b.GiveUpRecruits(22);
  EXPECT_FALSE(b.RecruitsUnchecked(22));
  // Enough robots at tick 30: the order (sent before the schedule) enters at 31.
  b.OrderArrived(5);
  b.OnRecruits(30, {});
  b.OnSchedule({{5, 31}});
  EXPECT_FALSE(b.RecruitsUnchecked(31));
  EXPECT_FALSE(b.OrdersMissing(31));
  // The other way round: the schedule first, then the order.
  b.OnRecruits(40, {{6, 40}});
  b.OnRecruits(45, {});
  b.OnSchedule({{6, 46}});
  EXPECT_TRUE(b.OrdersMissing(46));
  b.OrderArrived(6);
  EXPECT_FALSE(b.OrdersMissing(46));
}

TEST(LockstepBarrierTest, GivingUpOnAMissingScheduleLetsTheRunGoOn) {
  LockstepBarrier b;
  b.ExpectSchedule();
  EXPECT_TRUE(b.ScheduleMissing());
  EXPECT_TRUE(b.GiveUpOrders(1).empty());
  EXPECT_FALSE(b.ScheduleMissing());
  EXPECT_FALSE(b.OrdersMissing(2));
}

TEST(LockstepBarrierTest, EndAllAsksNobody) {
  LockstepBarrier b = TwoLive(1);
  b.EndAll();
  EXPECT_TRUE(b.AllAnswered());
  EXPECT_EQ(b.LiveCount(), 0u);
}

}  // namespace
}  // namespace sim
}  // namespace swarm_transport
