#include "swarm_transport/core/angle.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

namespace swarm_transport {
namespace core {
namespace {

constexpr double kTolerance = 1e-9;

TEST(AngleTest, SumWrapsPastFullTurn) {
  EXPECT_EQ(Angle(350) + Angle(20), Angle(10));
  EXPECT_NEAR((Angle(350) + Angle(20)).degrees(), 10.0, kTolerance);
}

TEST(AngleTest, NegativeAndLargeDegreesWrapIntoRange) {
  EXPECT_NEAR(Angle(-30).degrees(), 330.0, kTolerance);
  EXPECT_NEAR(Angle(-720).degrees(), 0.0, kTolerance);
  EXPECT_NEAR(Angle(725).degrees(), 5.0, kTolerance);
  EXPECT_NEAR((Angle(10) - Angle(20)).degrees(), 350.0, kTolerance);
}

// Angle's wrap as fmod gives it, bit for bit (the sign of a zero too): the constructor skips
// fmod's call where the result is exact arithmetic, and every run's files depend on each bit.
double FmodWrapped(double degrees) {
  double d = std::fmod(degrees, 360.0);
  if (d < 0.0) d += 360.0;
  if (d >= 360.0) d = 0.0;
  return d;
}

TEST(AngleTest, WrapsBitForBitAsFmod) {
  std::vector<double> inputs = {0.0,    -0.0,    360.0,   -360.0,   720.0, -720.0,
                                1080.0, -1080.0, 1e-300,  -1e-300,  1e-15, -1e-15,
                                359.99, -359.99, 719.999, -719.999, 1e20,  -1e20};
  for (const double edge : {360.0, -360.0, 720.0, -720.0, 0.0}) {
    inputs.push_back(std::nextafter(edge, 1e9));
    inputs.push_back(std::nextafter(edge, -1e9));
  }
  std::mt19937_64 gen(7);
  std::uniform_real_distribution<double> uniform(-1500.0, 1500.0);
  for (int i = 0; i < 100000; ++i) inputs.push_back(uniform(gen));
  for (const double x : inputs) {
    const double got = Angle(x).degrees();
    const double want = FmodWrapped(x);
    std::uint64_t got_bits = 0;
    std::uint64_t want_bits = 0;
    std::memcpy(&got_bits, &got, sizeof got);
    std::memcpy(&want_bits, &want, sizeof want);
    ASSERT_EQ(got_bits, want_bits) << "Angle(" << x << ")";
  }
  EXPECT_TRUE(std::isnan(Angle(std::nan("")).degrees()));
  EXPECT_TRUE(std::isnan(Angle(INFINITY).degrees()));
}

TEST(AngleTest, TinyNegativeWrapsToZeroNotToFullTurn) {
  // -1e-15 + 360 rounds to exactly 360, which is outside [0, 360).
  EXPECT_LT(Angle(-1e-15).degrees(), 360.0);
  EXPECT_EQ(Angle(-1e-15), Angle(0));
}

TEST(AngleTest, RadiansConvertBothWays) {
  EXPECT_NEAR(Angle(180).radians(), M_PI, kTolerance);
  EXPECT_NEAR(Angle::FromRadians(-M_PI / 2).degrees(), 270.0, kTolerance);
}

TEST(AngleTest, EqualityTreatsJustBelowFullTurnAsZero) {
  EXPECT_EQ(Angle(360.0 - 1e-12), Angle(0));
  EXPECT_NE(Angle(359.9), Angle(0));
}

TEST(AngleTest, SignedDifferenceTakesTheShortWay) {
  EXPECT_NEAR(Angle::SignedDifference(Angle(10), Angle(350)), 20.0, kTolerance);
  EXPECT_NEAR(Angle::SignedDifference(Angle(350), Angle(10)), -20.0, kTolerance);
  EXPECT_NEAR(Angle::SignedDifference(Angle(271), Angle(90)), -179.0, kTolerance);
  EXPECT_NEAR(Angle::SignedDifference(Angle(90), Angle(90)), 0.0, kTolerance);
}

TEST(AngleTest, SignedDifferenceOfOppositeHeadingsIsPlus180) {
  EXPECT_NEAR(Angle::SignedDifference(Angle(180), Angle(0)), 180.0, kTolerance);
  EXPECT_NEAR(Angle::SignedDifference(Angle(0), Angle(180)), 180.0, kTolerance);
}

TEST(AngleTest, CircularMeanOf45And315IsZero) {
  bool defined = false;
  EXPECT_EQ(CircularMean({Angle(45), Angle(315)}, &defined), Angle(0));
  EXPECT_TRUE(defined);
}

TEST(AngleTest, CircularMeanOfOppositeHeadingsIsUndefined) {
  bool defined = true;
  EXPECT_EQ(CircularMean({Angle(0), Angle(180)}, &defined), Angle(0));
  EXPECT_FALSE(defined);
  defined = true;
  EXPECT_EQ(CircularMean({Angle(90), Angle(270)}, &defined), Angle(0));
  EXPECT_FALSE(defined);
}

TEST(AngleTest, CircularMeanOfNothingIsUndefined) {
  bool defined = true;
  CircularMean({}, &defined);
  EXPECT_FALSE(defined);
}

TEST(AngleTest, CircularMeanWeighsEachAngle) {
  bool defined = false;
  EXPECT_EQ(CircularMean({Angle(0), Angle(90)}, &defined, {1.0, 1.0}), Angle(45));
  // atan2(sqrt(3), 1) = 60 degrees.
  EXPECT_EQ(CircularMean({Angle(0), Angle(90)}, &defined, {1.0, std::sqrt(3.0)}), Angle(60));
  EXPECT_TRUE(defined);
}

TEST(AngleTest, CircularMeanRejectsMismatchedWeights) {
  bool defined = false;
  EXPECT_THROW(CircularMean({Angle(0), Angle(90)}, &defined, {1.0}), std::invalid_argument);
}

// CircularMeanOfSums decides "defined" from the squared length where it is clearly on one side
// of 1e-9: the same answer as hypot's at and around the limit, at tiny (underflowing) and huge
// sums, and NaN.
TEST(AngleTest, CircularMeanOfSumsDefinedAsHypotSays) {
  std::vector<std::pair<double, double>> sums = {
      {0.0, 0.0},     {1e-9, 0.0},     {0.0, -1e-9}, {6e-10, 8e-10},      {1e-170, 1e-170},
      {1e200, 1e200}, {-1e-9, 1e-300}, {3.0, -4.0},  {std::nan(""), 1.0}, {1.0, std::nan("")}};
  for (double scale :
       {1.0 - 1e-8, 1.0 - 1e-10, 1.0 - 1e-15, 1.0 + 1e-15, 1.0 + 1e-10, 1.0 + 1e-8}) {
    sums.emplace_back(1e-9 * scale, 0.0);
    sums.emplace_back(0.6e-9 * scale, -0.8e-9 * scale);
    sums.emplace_back(-0.7071067811865476e-9 * scale, 0.7071067811865476e-9 * scale);
  }
  for (const auto& s : sums) {
    bool defined = true;
    CircularMeanOfSums(s.first, s.second, &defined);
    EXPECT_EQ(defined, std::hypot(s.first, s.second) >= 1e-9) << s.first << ", " << s.second;
  }
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
