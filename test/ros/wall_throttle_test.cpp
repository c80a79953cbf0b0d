// WarnThrottle (wall_throttle.h): one warning per period of wall time, counting the ones held
// back. Driven with given wall times, so nothing here depends on how fast the test runs.
#include "swarm_transport/ros/common/wall_throttle.h"

#include <gtest/gtest.h>

namespace swarm_transport {
namespace {

ros::WallTime At(double s) { return ros::WallTime(s); }

TEST(WarnThrottleTest, TheFirstCallIsDueWhateverTheClockSays) {
  WarnThrottle throttle(5.0);
  EXPECT_TRUE(throttle.Due(At(0.0)));  // a zero time is not "never warned"
  WarnThrottle other(5.0);
  EXPECT_TRUE(other.Due(At(1e9)));
  EXPECT_EQ(other.suppressed(), 0u);
}

TEST(WarnThrottleTest, OneLinePerPeriodAndTheHeldBackOnesAreCounted) {
  WarnThrottle throttle(5.0);
  ASSERT_TRUE(throttle.Due(At(100.0)));
  EXPECT_FALSE(throttle.Due(At(100.0)));
  EXPECT_FALSE(throttle.Due(At(102.0)));
  EXPECT_FALSE(throttle.Due(At(104.999)));
  EXPECT_EQ(throttle.suppressed(), 0u) << "counted only when the next line goes out";
  EXPECT_EQ(throttle.AndMore("rejections"), "");
  EXPECT_TRUE(throttle.Due(At(105.0)));
  EXPECT_EQ(throttle.suppressed(), 3u);
  EXPECT_EQ(throttle.AndMore("rejections"), " (and 3 more rejections since the last such line)");
  // The period counts from the last true, not from the first.
  EXPECT_FALSE(throttle.Due(At(109.0)));
  EXPECT_TRUE(throttle.Due(At(110.5)));
  EXPECT_EQ(throttle.suppressed(), 1u);
  EXPECT_TRUE(throttle.Due(At(200.0)));
  EXPECT_EQ(throttle.suppressed(), 0u);
  EXPECT_EQ(throttle.AndMore("rejections"), "");
}

TEST(WarnThrottleTest, TheDefaultPeriodIsFiveSeconds) {
  WarnThrottle throttle;
  EXPECT_EQ(throttle.period_s(), WarnThrottle::kDefaultPeriodS);
  EXPECT_EQ(WarnThrottle::kDefaultPeriodS, 5.0);
  ASSERT_TRUE(throttle.Due(At(10.0)));
  EXPECT_FALSE(throttle.Due(At(14.9)));
  EXPECT_TRUE(throttle.Due(At(15.0)));
}

TEST(WarnThrottleTest, ThrottlesAreIndependent) {
  WarnThrottle a(5.0), b(5.0);
  ASSERT_TRUE(a.Due(At(1.0)));
  EXPECT_TRUE(b.Due(At(1.0)));
  EXPECT_FALSE(a.Due(At(2.0)));
  EXPECT_FALSE(b.Due(At(2.0)));
}

TEST(WarnThrottleTest, TheRealClockVersionLetsTheFirstLineThrough) {
  WarnThrottle throttle(3600.0);
  EXPECT_TRUE(throttle.Due());
}

}  // namespace
}  // namespace swarm_transport
