#include "swarm_transport/core/hardware.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "validator_fixture.h"

namespace swarm_transport {
namespace core {
namespace {

using namespace validator_testing;  // NOLINT: the fixture of every validator test

TEST(HardwareOptionsTest, DefaultsAreValid) { EXPECT_EQ(HardwareOptions().Validate(), ""); }

TEST(HardwareOptionsTest, EachBadValueNamesItsParameter) {
  using P = HardwareOptions;
  std::vector<Violation<P>> v;
  Add<P, double>(&v, "~max_linear_m_s", &P::max_linear_m_s, {0.0, -1.0, kNan, kInf});
  Add<P, double>(&v, "~max_angular_rad_s", &P::max_angular_rad_s, {0.0, -1.0, kNan, kInf});
  Add<P, double>(&v, "~pose_timeout_s", &P::pose_timeout_s, {0.0, -0.1, kNan, kInf});
  Add<P, double>(&v, "~heard_timeout_s", &P::heard_timeout_s, {0.0, kNan, kInf});
  Add<P, double>(&v, "/swarm/radio_loss", &P::radio_loss, {-0.01, 1.01, kNan});
  v.push_back({"no odometry topic", [](P* p) { p->odom_topic = ""; }, "~odom_topic"});
  v.push_back({"tf without a base frame",
               [](P* p) {
                 p->pose_source = PoseSource::kTf;
                 p->base_frame = "";
               },
               "~base_frame"});
  v.push_back({"tf from a frame to itself",
               [](P* p) {
                 p->pose_source = PoseSource::kTf;
                 p->base_frame = "map";
               },
               "must differ"});
  ExpectEachViolationNamed(P(), v);
  P odom_only;  // frames matter only for tf
  odom_only.base_frame = "";
  EXPECT_EQ(odom_only.Validate(), "");
}

TEST(HardwareOptionsTest, ParsesPoseSources) {
  PoseSource s = PoseSource::kOdom;
  EXPECT_TRUE(ParsePoseSource("tf", &s));
  EXPECT_EQ(s, PoseSource::kTf);
  EXPECT_STREQ(PoseSourceName(s), "tf");
  EXPECT_FALSE(ParsePoseSource("mocap", &s));
  EXPECT_EQ(s, PoseSource::kTf);
  EXPECT_TRUE(ParsePoseSource("odom", &s));
  EXPECT_EQ(s, PoseSource::kOdom);
}

TEST(LimitSpeedTest, ClampsEachPartAndStandsOnNonFinite) {
  Velocity v = LimitSpeed({2.0, -5.0}, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(v.linear, 0.5);
  EXPECT_DOUBLE_EQ(v.angular, -1.0);
  v = LimitSpeed({-0.2, 0.3}, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(v.linear, -0.2);
  EXPECT_DOUBLE_EQ(v.angular, 0.3);
  v = LimitSpeed({std::nan(""), std::numeric_limits<double>::infinity()}, 0.5, 1.0);
  EXPECT_DOUBLE_EQ(v.linear, 0.0);
  EXPECT_DOUBLE_EQ(v.angular, 0.0);
}

TEST(PoseWatchTest, StaleWithoutPoseThenFreshThenStaleOnceEach) {
  PoseWatch watch(0.5);
  PoseWatch::Change change = PoseWatch::Change::kNone;
  EXPECT_FALSE(watch.Check(10.0, &change));
  EXPECT_EQ(change, PoseWatch::Change::kStale);
  EXPECT_FALSE(watch.Check(10.1, &change));
  EXPECT_EQ(change, PoseWatch::Change::kNone);  // said once
  watch.Took(10.2);
  EXPECT_TRUE(watch.Check(10.3, &change));
  EXPECT_EQ(change, PoseWatch::Change::kFresh);
  EXPECT_TRUE(watch.Check(10.7, &change));  // 0.5 s old: still fresh
  EXPECT_EQ(change, PoseWatch::Change::kNone);
  EXPECT_FALSE(watch.Check(10.71, &change));
  EXPECT_EQ(change, PoseWatch::Change::kStale);
  EXPECT_NEAR(watch.AgeS(10.71), 0.51, 1e-9);
  watch.Took(9.0);  // an older pose arriving late does not make it younger
  EXPECT_FALSE(watch.Check(10.72, &change));
  watch.Took(10.72);
  EXPECT_TRUE(watch.Check(10.72, &change));
  EXPECT_EQ(change, PoseWatch::Change::kFresh);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
