// What a robot re-sends to a restarted dispatcher or recorder (ros/common/mission_resend.h): the
// latest status of each mission it led, and nothing live of a mission it heard end (issue 29: a
// first leader replaced by a promoted robot re-sent its mission as TRANSPORT after every
// dispatcher restart, long after the mission had ended; the dispatcher took it up again).
#include "swarm_transport/ros/common/mission_resend.h"

#include <gtest/gtest.h>

#include "status_fixture.h"

namespace swarm_transport {
namespace {

using fixtures::Status;

TEST(MissionResenderTest, AMissionHeardEndingIsForgottenUnlessItEndedItItself) {
  MissionResender resender;
  resender.Remember(Status(1, Mission_Status::TRANSPORT), nullptr);  // led, then replaced
  resender.Remember(Status(2, Mission_Status::DONE), nullptr);       // ended by itself
  resender.Remember(Status(3, Mission_Status::LOADING), nullptr);    // still live
  ASSERT_EQ(resender.remembered(), 3u);
  resender.Ended(1);
  resender.Ended(2);
  resender.Ended(9);  // never led: nothing to forget
  EXPECT_EQ(resender.remembered(), 2u);
  EXPECT_FALSE(resender.Remembers(1));
  EXPECT_TRUE(resender.Remembers(2));  // its own DONE tells a restarted dispatcher it ended
  EXPECT_TRUE(resender.Remembers(3));
}

}  // namespace
}  // namespace swarm_transport
