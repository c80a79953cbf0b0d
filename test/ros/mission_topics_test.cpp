// A real-time robot's mission publishers go after it led nothing for a while
// (ros/common/mission_topics.h, PublishersLinger): a robot that led once must not hold a
// connection per subscriber and topic for the rest of its life (issue 29: the soak's growing
// open descriptors).
#include "swarm_transport/ros/common/mission_topics.h"

#include <gtest/gtest.h>

namespace swarm_transport {
namespace {

TEST(PublishersLingerTest, DueOnlyAfterLeadingNothingForTheWholeLinger) {
  PublishersLinger linger(5.0);
  EXPECT_FALSE(linger.Due(true, 0.0));
  EXPECT_FALSE(linger.Due(true, 100.0));   // leading: never, however long
  EXPECT_FALSE(linger.Due(false, 100.0));  // the count starts
  EXPECT_FALSE(linger.Due(false, 104.9));
  EXPECT_TRUE(linger.Due(false, 105.0));
}

TEST(PublishersLingerTest, LeadingAgainStartsTheCountAfresh) {
  PublishersLinger linger(5.0);
  EXPECT_FALSE(linger.Due(false, 0.0));
  EXPECT_FALSE(linger.Due(false, 4.0));
  EXPECT_FALSE(linger.Due(true, 4.5));   // a new mission led
  EXPECT_FALSE(linger.Due(false, 6.0));  // idle again from 6 s
  EXPECT_FALSE(linger.Due(false, 10.9));
  EXPECT_TRUE(linger.Due(false, 11.0));
}

TEST(PublishersLingerTest, AfterReleaseTheNextIdleSpellCountsFromItsStart) {
  PublishersLinger linger(5.0);
  EXPECT_FALSE(linger.Due(false, 0.0));
  EXPECT_TRUE(linger.Due(false, 5.0));
  // Advertised again later (it leads again, then not): a whole linger again.
  EXPECT_FALSE(linger.Due(false, 50.0));
  EXPECT_FALSE(linger.Due(false, 54.0));
  EXPECT_TRUE(linger.Due(false, 55.0));
}

TEST(MissionPublishersTest, NothingAdvertisedIsNothingToRelease) {
  MissionPublishers pubs;
  EXPECT_FALSE(pubs.advertised());
  EXPECT_FALSE(pubs.Release(false, 0.0));
  EXPECT_FALSE(pubs.Release(false, 100.0));
}

}  // namespace
}  // namespace swarm_transport
