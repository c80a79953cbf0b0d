#include "swarm_transport/sim/lockstep_barrier.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace swarm_transport {
namespace sim {
namespace {

using Command = LockstepBarrier::Command;

core::Velocity Forward(double linear) {
  core::Velocity v;
  v.linear = linear;
  return v;
}

// Robots 3 and 7 answer with a command.
void BothAnswer(LockstepBarrier* b) {
  b->OnCommand(3, Forward(0.1));
  b->OnCommand(7, Forward(0.1));
}

// Two live robots in one host process ("/host"), tick `tick` asked.
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

TEST(LockstepBarrierTest, ATickIsCompleteWhenEveryLiveRobotAnswered) {
  LockstepBarrier b = TwoLive();
  EXPECT_FALSE(b.AllAnswered());
  EXPECT_EQ(b.OnCommand(3, Forward(0.1)), Command::kAnswer);
  EXPECT_FALSE(b.AllAnswered());
  EXPECT_EQ(b.Late(), (std::vector<std::uint16_t>{7}));
  EXPECT_EQ(b.OnCommand(7, Forward(0.2)), Command::kAnswer);
  EXPECT_TRUE(b.AllAnswered());
  EXPECT_DOUBLE_EQ(b.CommandOf(3).linear, 0.1);
  EXPECT_DOUBLE_EQ(b.CommandOf(7).linear, 0.2);
  // A second command in the same tick was not asked for.
  EXPECT_EQ(b.OnCommand(7, Forward(0.3)), Command::kUnsolicited);
  EXPECT_DOUBLE_EQ(b.CommandOf(7).linear, 0.2);
}

TEST(LockstepBarrierTest, ARobotThatIsNotLiveIsOutsideTheBarrier) {
  LockstepBarrier b;
  b.Add(1);
  b.StartTick(1);
  b.Ask(1);  // not live: not asked
  EXPECT_TRUE(b.AllAnswered());
  EXPECT_EQ(b.OnCommand(1, Forward(0.1)), Command::kOutside);
  EXPECT_EQ(b.OnCommand(99, Forward(0.1)), Command::kOutside);  // unknown
}

TEST(LockstepBarrierTest, ALateAnswerIsIgnoredAndTheRobotStands) {
  LockstepBarrier b = TwoLive(1);
  b.OnCommand(3, Forward(0.1));
  // Robot 7 misses tick 1; tick 2 asks both again.
  b.StartTick(2);
  b.Ask(3);
  b.Ask(7);
  EXPECT_EQ(b.OnCommand(7, Forward(0.5)), Command::kStale);  // its answer to tick 1
  EXPECT_FALSE(b.AllAnswered());
  EXPECT_DOUBLE_EQ(b.CommandOf(7).linear, 0.0);  // it stands
  EXPECT_EQ(b.OnCommand(7, Forward(0.6)), Command::kAnswer);
  EXPECT_DOUBLE_EQ(b.CommandOf(7).linear, 0.6);
}

TEST(LockstepBarrierTest, ARobotThatMissedAPerceptionIsResynchronised) {
  LockstepBarrier b = TwoLive(1);
  b.Ask(7);  // two perceptions, but it only ever answers one per tick
  EXPECT_EQ(b.OnCommand(7, Forward(0.1)), Command::kStale);
  EXPECT_FALSE(b.Resynchronise(3));  // nothing stale about robot 3
  EXPECT_TRUE(b.Resynchronise(7));
  b.StartTick(2);
  b.Ask(7);
  EXPECT_EQ(b.OnCommand(7, Forward(0.2)), Command::kAnswer);
}

// Race fixed in a95f00d: a robot that publishes tick_done is waited for from its first tick,
// even when its tick_done arrives after its command (the old logic closed the tick on the
// command alone until the first tick_done had been seen).
TEST(LockstepBarrierTest, WaitsForTickDoneFromTheFirstTick) {
  LockstepBarrier b;
  b.Add(3);
  b.SendsTickDone(3);  // its tick_done publisher is connected
  b.MakeLive(3);
  b.StartTick(0);
  b.Ask(3);
  b.OnCommand(3, Forward(0.1));
  EXPECT_FALSE(b.AllAnswered());
  b.OnTickDone(3, "/host", 0, 0);
  EXPECT_TRUE(b.AllAnswered());
}

TEST(LockstepBarrierTest, ATickDoneOfAnotherTickDoesNotComplete) {
  LockstepBarrier b = TwoLive(5);
  BothAnswer(&b);
  b.OnTickDone(3, "/host", 4, 0);  // the previous tick's
  b.OnTickDone(7, "/host", 5, 0);
  EXPECT_FALSE(b.AllAnswered());
  b.OnTickDone(3, "/host", 5, 0);
  EXPECT_TRUE(b.AllAnswered());
}

// Race fixed in a95f00d: mission messages are counted per publishing node. A status the
// dispatcher (another node) sent must not stand in for one a robot announced, or the tick
// closes before the robot's message arrived and it is relayed a tick late.
TEST(LockstepBarrierTest, AnnouncedMessagesAreCountedPerPublisher) {
  LockstepBarrier b = TwoLive(1);
  BothAnswer(&b);
  b.OnTickDone(3, "/host", 1, 1);  // robot 3 sent one mission message
  b.OnTickDone(7, "/host", 1, 0);
  EXPECT_FALSE(b.AllAnswered());
  b.OnRobotMessage("/mission_dispatcher");
  EXPECT_FALSE(b.AllAnswered());  // a count blind to publishers closed the tick here
  EXPECT_EQ(b.Late(), (std::vector<std::uint16_t>{3, 7}));  // one process: both wait
  b.OnRobotMessage("/host");
  EXPECT_TRUE(b.AllAnswered());
}

TEST(LockstepBarrierTest, ARobotMovedToAnotherProcessTakesItsCountAlong) {
  LockstepBarrier b = TwoLive(1);
  BothAnswer(&b);
  b.OnTickDone(3, "/host_a", 1, 2);
  b.OnTickDone(7, "/host_a", 1, 0);
  b.OnRobotMessage("/host_a");
  b.OnRobotMessage("/host_a");
  EXPECT_TRUE(b.AllAnswered());
  // Robot 3 comes back in another process with a fresh count of 1.
  b.StartTick(2);
  b.Ask(3);
  b.Ask(7);
  BothAnswer(&b);
  b.OnTickDone(3, "/host_b", 2, 1);
  b.OnTickDone(7, "/host_a", 2, 0);
  EXPECT_FALSE(b.AllAnswered());  // /host_b owes one message
  b.OnRobotMessage("/host_b");
  EXPECT_TRUE(b.AllAnswered());  // /host_a no longer owes robot 3's two
}

TEST(LockstepBarrierTest, RemovingARobotItWaitsForEndsTheWait) {
  LockstepBarrier b = TwoLive(1);
  b.OnCommand(3, Forward(0.1));
  EXPECT_FALSE(b.AllAnswered());
  b.Remove(7);
  EXPECT_TRUE(b.AllAnswered());
  EXPECT_FALSE(b.Has(7));
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
