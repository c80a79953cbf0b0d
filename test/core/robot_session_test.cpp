// What a robot's session says of the mission messages it refuses: a warning for bad input, a
// debug line for what is routine.
#include "swarm_transport/core/robot_session.h"

#include <gtest/gtest.h>

#include <set>

#include "fixtures.h"

namespace swarm_transport {
namespace core {
namespace {

using Say = RobotSession::Taken::Say;

SwarmConfig Params() {
  SwarmConfig p;
  p.flocking.local_range_m = 1.0;
  p.flocking.speed_m_per_tick = 0.1;
  p.tick_period_s = 1.0;
  return p;
}

const Sender kDispatcher{SenderKind::kDispatcher, 0};

TEST(RobotSessionTest, AReSentSignalOfAMissionItDoesNotHoldIsRoutine) {
  RobotSession session(0, Params());
  const std::set<std::uint16_t> robots = fixtures::Robots(3);
  const RobotSession::Taken order = session.Take(fixtures::Thesis(7), kDispatcher, robots);
  ASSERT_EQ(order.why, "");
  EXPECT_TRUE(order.first_leader);
  // Mission 7 is held and not LOADING: a LOADED now is bad input.
  const RobotSession::Taken early =
      session.Take(Signal{7, MissionEventKind::kLoaded, 0}, kDispatcher, robots);
  EXPECT_NE(early.why, "");
  EXPECT_EQ(early.say, Say::kWarn);
  // Mission 8 is none of its own (ended here, or never heard): refused, said at debug level,
  // because the dispatcher re-sends a signal while its view of the mission lags its end.
  const RobotSession::Taken late =
      session.Take(Signal{8, MissionEventKind::kUnloaded, 0}, kDispatcher, robots);
  EXPECT_NE(late.why, "");
  EXPECT_EQ(late.say, Say::kDebug);
}

TEST(RobotSessionTest, TheOrderItHoldsAgainIsRoutineAnotherWithItsIdIsNot) {
  RobotSession session(0, Params());
  const std::set<std::uint16_t> robots = fixtures::Robots(3);
  ASSERT_EQ(session.Take(fixtures::Thesis(7), kDispatcher, robots).why, "");
  // The dispatcher sends the QUEUED orders to a robot as it connects, perhaps just after it
  // published one of them: the same order twice is refused quietly.
  const RobotSession::Taken again = session.Take(fixtures::Thesis(7), kDispatcher, robots);
  EXPECT_NE(again.why, "");
  EXPECT_EQ(again.say, Say::kDebug);
  // A different order under the live id is bad input.
  MissionSpec other = fixtures::Thesis(7);
  other.target.x += 1.0;
  const RobotSession::Taken clash = session.Take(other, kDispatcher, robots);
  EXPECT_NE(clash.why, "");
  EXPECT_EQ(clash.say, Say::kWarn);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
