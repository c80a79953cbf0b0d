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

using core::DispatcherAnswer;
using core::MissionEventKind;
using core::MissionPhase;
using core::StatusKey;
using Event = LockstepBarrier::EventKey;

// The dispatcher's answer to the positions of tick `checked` (no recruit: nothing held later).
DispatcherAnswer Positions(std::uint64_t checked, std::uint64_t hold_from = 0) {
  DispatcherAnswer a;
  a.has_positions = true;
  a.checked_tick = checked;
  a.hold_from_tick = hold_from;
  return a;
}

core::Signal Loaded(std::uint16_t mission_id) {
  return core::Signal{mission_id, MissionEventKind::kLoaded, 0};
}

// With a dispatcher, tick 1 on waits for its first answer to positions (tick 0 runs: it answers
// the positions of tick 0); an answer after a status before any positions does not count.
TEST(LockstepBarrierTest, TickOneWaitsForTheDispatchersFirstAnswer) {
  LockstepBarrier none;
  EXPECT_FALSE(none.DispatcherPending(1));  // no dispatcher expected
  LockstepBarrier b;
  b.ExpectDispatcher();
  EXPECT_FALSE(b.DispatcherPending(0));
  EXPECT_TRUE(b.DispatcherPending(1));
  EXPECT_TRUE(b.WaitsFor(1).first);
  DispatcherAnswer before = Positions(0, 1);
  before.has_positions = false;
  b.OnDispatcherAnswer(before);
  EXPECT_TRUE(b.DispatcherPending(1));
  b.OnDispatcherAnswer(Positions(0));
  EXPECT_FALSE(b.DispatcherPending(1));
  EXPECT_FALSE(b.DispatcherPending(50));  // it holds nothing later
}

// Every status relayed from the robots waits for the answer naming it, and what that answer
// names (a LOADED) for its arrival, whichever of the two topics delivers first. The barrier does
// not know which phase owes what: an answer that names no event releases the tick.
TEST(LockstepBarrierTest, ARelayedStatusWaitsForItsAnswerAndWhatItNames) {
  LockstepBarrier b;
  b.ExpectDispatcher();
  b.OnDispatcherAnswer(Positions(0));
  const StatusKey gathering{4, MissionPhase::kGathering, 3};
  b.StatusRelayed(gathering);
  EXPECT_TRUE(b.DispatcherPending(4));
  ASSERT_EQ(b.WaitsFor(4).statuses.size(), 1u);
  DispatcherAnswer took = Positions(3);
  took.status = StatusKey{4, MissionPhase::kGathering, 2};  // another status: not this one
  b.OnDispatcherAnswer(took);
  EXPECT_TRUE(b.DispatcherPending(4));
  took.status = gathering;
  b.OnDispatcherAnswer(took);
  EXPECT_FALSE(b.DispatcherPending(4));
  // LOADING: its answer names a LOADED, which arrives after it.
  const StatusKey loading{4, MissionPhase::kLoading, 9};
  b.StatusRelayed(loading);
  took.status = loading;
  took.events = {Loaded(4)};
  b.OnDispatcherAnswer(took);
  EXPECT_TRUE(b.DispatcherPending(10));
  EXPECT_EQ(b.WaitsFor(10).events, (std::vector<Event>{{4, 1}}));
  b.EventArrived({4, 1});
  EXPECT_FALSE(b.DispatcherPending(10));
  // UNLOADING: the UNLOADED overtakes the answer naming it.
  const StatusKey unloading{4, MissionPhase::kUnloading, 20};
  b.StatusRelayed(unloading);
  b.EventArrived({4, 2});
  EXPECT_TRUE(b.DispatcherPending(21));
  took.status = unloading;
  took.events = {core::Signal{4, MissionEventKind::kUnloaded, 23}};
  b.OnDispatcherAnswer(took);
  EXPECT_FALSE(b.DispatcherPending(21));
}

// A mission's end forgets what arrived for it unnamed (a user's LOADED): the next mission with
// that id waits for its own.
TEST(LockstepBarrierTest, AnEndedMissionsUnnamedEventsAreForgotten) {
  LockstepBarrier b;
  b.EventArrived({4, 1});  // a user's LOADED, named by no answer
  b.Forget(4);
  DispatcherAnswer took;
  took.events = {Loaded(4)};
  b.OnDispatcherAnswer(took);
  EXPECT_TRUE(b.DispatcherPending(5));
}

// Missions at a defined tick (issue 10, item 4): each order an answer names waits from its start
// tick until it arrived, whichever of the two topics delivers first.
TEST(LockstepBarrierTest, NamedOrdersAreWaitedForFromTheirStartTick) {
  LockstepBarrier b;
  b.ExpectDispatcher();
  b.OrderArrived(7);  // the order overtook the answer
  DispatcherAnswer first = Positions(0);
  first.orders = {{7, 10}, {8, 10}, {9, 30}};
  b.OnDispatcherAnswer(first);
  EXPECT_FALSE(b.DispatcherPending(1));
  EXPECT_FALSE(b.DispatcherPending(9));
  EXPECT_TRUE(b.DispatcherPending(10));  // 8 is due
  EXPECT_EQ(b.WaitsFor(10).orders, (std::vector<std::uint16_t>{8}));
  b.OrderArrived(8);
  EXPECT_FALSE(b.DispatcherPending(10));
  EXPECT_TRUE(b.DispatcherPending(30));
  EXPECT_EQ(b.GiveUpDispatcher(30).orders, (std::vector<std::uint16_t>{9}));
  EXPECT_FALSE(b.DispatcherPending(31));
  b.OrderArrived(12);  // a raw order nobody named: nothing to wait for
  EXPECT_FALSE(b.DispatcherPending(40));
}

// Statist as dispatcher (SPEC 9.4), seen from the barrier: the answers hold every tick from
// hold_from_tick on until the answer to the previous tick's positions arrived.
TEST(LockstepBarrierTest, AnAnswerHoldsLaterTicksForTheNextAnswers) {
  LockstepBarrier b;
  b.ExpectDispatcher();
  b.OnDispatcherAnswer(Positions(0, 21));
  EXPECT_FALSE(b.DispatcherPending(20));
  EXPECT_TRUE(b.DispatcherPending(21));  // it has not answered tick 20
  EXPECT_TRUE(b.WaitsFor(21).answer);
  EXPECT_FALSE(b.WaitsFor(21).first);
  b.OnDispatcherAnswer(Positions(20, 21));
  EXPECT_FALSE(b.DispatcherPending(21));
  EXPECT_TRUE(b.DispatcherPending(22));
  b.GiveUpDispatcher(22);
  EXPECT_FALSE(b.DispatcherPending(22));
  EXPECT_TRUE(b.DispatcherPending(23));  // given up for one tick only
  // An older answer arriving late does not undo a newer one.
  b.OnDispatcherAnswer(Positions(30, 21));
  b.OnDispatcherAnswer(Positions(25, 21));
  EXPECT_FALSE(b.DispatcherPending(31));
  // Its order, named for the next tick, is waited for; the hold ends with the recruit.
  DispatcherAnswer found = Positions(31, 0);
  found.orders = {{5, 32}};
  b.OnDispatcherAnswer(found);
  EXPECT_TRUE(b.DispatcherPending(32));
  b.OrderArrived(5);
  EXPECT_FALSE(b.DispatcherPending(32));
  EXPECT_FALSE(b.DispatcherPending(100));
}

TEST(LockstepBarrierTest, GivingUpOnTheFirstAnswerLetsTheRunGoOn) {
  LockstepBarrier b;
  b.ExpectDispatcher();
  b.StatusRelayed({4, MissionPhase::kGathering, 0});
  const LockstepBarrier::DispatcherWait given_up = b.GiveUpDispatcher(1);
  EXPECT_TRUE(given_up.first);
  EXPECT_EQ(given_up.statuses.size(), 1u);
  EXPECT_EQ(given_up.Text(1), "no first answer; no answer to the GATHERING of mission 4 (tick 0)");
  EXPECT_FALSE(b.DispatcherPending(1));
  EXPECT_FALSE(b.DispatcherPending(2));
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
