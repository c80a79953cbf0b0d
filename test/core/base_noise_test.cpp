#include "swarm_transport/sim/base_noise.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "validator_fixture.h"

namespace swarm_transport {
namespace sim {
namespace {

using namespace validator_testing;  // NOLINT: the fixture of every validator test

TEST(BaseNoiseTest, EachBadValueNamesItsParameter) {
  using P = BaseNoiseParams;
  std::vector<Violation<P>> v;
  Add<P, double>(&v, "~position_noise_m", &P::position_noise_m, {-0.001, 1.01, kNan, kInf});
  Add<P, double>(&v, "~heading_noise_deg", &P::heading_noise_deg, {-1.0, 181.0, kNan});
  Add<P, double>(&v, "~heading_drift_deg", &P::heading_drift_deg, {-1.0, 181.0, kInf});
  ExpectEachViolationNamed(P(), v);
}

TEST(BaseNoiseTest, WithoutNoiseTheTruth) {
  BaseNoise noise(BaseNoiseParams(), 1, 3);
  const core::Pose2 truth{{2.0, 3.0}, core::Angle(40.0)};
  const core::Pose2 measured = noise.Measure(truth);
  EXPECT_EQ(measured.position.x, 2.0);
  EXPECT_EQ(measured.position.y, 3.0);
  EXPECT_EQ(measured.heading.degrees(), 40.0);
  EXPECT_EQ(noise.Drift(truth.heading).degrees(), 40.0);
  EXPECT_FALSE(BaseNoiseParams().Any());
}

TEST(BaseNoiseTest, DeviationsAsAskedAndTheSameForASeed) {
  BaseNoiseParams params;
  params.position_noise_m = 0.01;
  params.heading_drift_deg = 0.5;
  BaseNoise a(params, 7, 2);
  BaseNoise b(params, 7, 2);
  BaseNoise other(params, 7, 3);
  const core::Pose2 truth{{5.0, 5.0}, core::Angle(90.0)};
  double sum = 0.0, sum2 = 0.0, drift2 = 0.0;
  bool differs = false;
  const int n = 20000;
  for (int i = 0; i < n; ++i) {
    const core::Pose2 m = a.Measure(truth);
    EXPECT_EQ(m.position.x, b.Measure(truth).position.x);
    differs = differs || other.Measure(truth).position.x != m.position.x;
    sum += m.position.x - 5.0;
    sum2 += (m.position.x - 5.0) * (m.position.x - 5.0);
    const double d = a.Drift(truth.heading).degrees() - 90.0;
    b.Drift(truth.heading);
    drift2 += d * d;
  }
  EXPECT_TRUE(differs);
  EXPECT_NEAR(sum / n, 0.0, 0.0005);
  EXPECT_NEAR(std::sqrt(sum2 / n), 0.01, 0.0005);
  EXPECT_NEAR(std::sqrt(drift2 / n), 0.5, 0.02);
}

}  // namespace
}  // namespace sim
}  // namespace swarm_transport
