// Clock, comm, placement and deploy modes: every name parses to its mode and back; anything else is
// refused.
#include "swarm_transport/core/modes.h"

#include <gtest/gtest.h>

namespace swarm_transport {
namespace core {
namespace {

TEST(ModesTest, NamesRoundTripAndUnknownNamesChangeNothing) {
  for (const Clock c : {Clock::kRealtime, Clock::kLockstep}) {
    Clock parsed = c == Clock::kRealtime ? Clock::kLockstep : Clock::kRealtime;
    ASSERT_TRUE(ParseClock(ClockName(c), &parsed));
    EXPECT_EQ(parsed, c);
  }
  for (const Comm c : {Comm::kLocal, Comm::kBroadcast}) {
    Comm parsed = c == Comm::kLocal ? Comm::kBroadcast : Comm::kLocal;
    ASSERT_TRUE(ParseComm(CommName(c), &parsed));
    EXPECT_EQ(parsed, c);
  }
  for (const Placement p : {Placement::kRandom, Placement::kCorner, Placement::kFile}) {
    Placement parsed = p == Placement::kFile ? Placement::kRandom : Placement::kFile;
    ASSERT_TRUE(ParsePlacement(PlacementName(p), &parsed));
    EXPECT_EQ(parsed, p);
  }
  for (const Deploy d : {Deploy::kProcess, Deploy::kHost, Deploy::kHostSim, Deploy::kNone}) {
    Deploy parsed = d == Deploy::kNone ? Deploy::kProcess : Deploy::kNone;
    ASSERT_TRUE(ParseDeploy(DeployName(d), &parsed));
    EXPECT_EQ(parsed, d);
  }
  Deploy deploy = Deploy::kHostSim;
  EXPECT_FALSE(ParseDeploy("hostsim", &deploy));
  EXPECT_FALSE(ParseDeploy("batch", &deploy));
  EXPECT_EQ(deploy, Deploy::kHostSim);
  Placement placement = Placement::kCorner;
  EXPECT_FALSE(ParsePlacement("grid", &placement));
  EXPECT_EQ(placement, Placement::kCorner);
  Clock clock = Clock::kLockstep;
  EXPECT_FALSE(ParseClock("Lockstep", &clock));
  EXPECT_FALSE(ParseClock("", &clock));
  EXPECT_EQ(clock, Clock::kLockstep);
  Comm comm = Comm::kBroadcast;
  EXPECT_FALSE(ParseComm("shout", &comm));
  EXPECT_EQ(comm, Comm::kBroadcast);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
