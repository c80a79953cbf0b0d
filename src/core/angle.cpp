#include "swarm_transport/core/angle.h"

#include <cmath>
#include <stdexcept>

namespace swarm_transport {
namespace core {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kFullTurnDeg = 360.0;
constexpr double kEqualToleranceDeg = 1e-9;
// Below this length the summed unit vectors give no direction [T5.2: 0 and 180 cancel].
constexpr double kUndefinedMeanLength = 1e-9;

}  // namespace

Angle::Angle(double degrees) {
  // fmod(degrees, 360) without its call where it is exact arithmetic: the value itself within
  // one turn, one turn off within two (x - 360 is exact there, Sterbenz), as fmod gives.
  if (std::fabs(degrees) < kFullTurnDeg) {
    degrees_ = degrees;
  } else if (degrees >= kFullTurnDeg && degrees < 2.0 * kFullTurnDeg) {
    degrees_ = degrees - kFullTurnDeg;
  } else if (degrees < -kFullTurnDeg && degrees > -2.0 * kFullTurnDeg) {  // -360: fmod says -0
    degrees_ = degrees + kFullTurnDeg;
  } else {
    degrees_ = std::fmod(degrees, kFullTurnDeg);
  }
  if (degrees_ < 0.0) degrees_ += kFullTurnDeg;
  // A tiny negative input becomes 360 - epsilon, which rounds to exactly 360.
  if (degrees_ >= kFullTurnDeg) degrees_ = 0.0;
}

Angle Angle::FromRadians(double radians) { return Angle(radians * 180.0 / kPi); }

double Angle::radians() const { return degrees_ * kPi / 180.0; }

Angle Angle::operator+(Angle other) const { return Angle(degrees_ + other.degrees_); }

Angle Angle::operator-(Angle other) const { return Angle(degrees_ - other.degrees_); }

bool Angle::operator==(Angle other) const {
  const double diff = std::fabs(degrees_ - other.degrees_);
  return diff <= kEqualToleranceDeg || kFullTurnDeg - diff <= kEqualToleranceDeg;
}

double Angle::SignedDifference(Angle to, Angle from) {
  double diff = to.degrees_ - from.degrees_;  // in (-360, 360) as both are wrapped
  if (diff > 180.0) diff -= kFullTurnDeg;
  if (diff <= -180.0) diff += kFullTurnDeg;
  return diff;
}

Angle CircularMean(const std::vector<Angle>& angles, bool* defined,
                   const std::vector<double>& weights) {
  if (!weights.empty() && weights.size() != angles.size()) {
    throw std::invalid_argument("CircularMean: weights must be empty or match the angles");
  }
  double sum_x = 0.0;
  double sum_y = 0.0;
  for (std::size_t i = 0; i < angles.size(); ++i) {
    const double weight = weights.empty() ? 1.0 : weights[i];
    const double radians = angles[i].radians();
    sum_x += weight * std::cos(radians);
    sum_y += weight * std::sin(radians);
  }
  return CircularMeanOfSums(sum_x, sum_y, defined);
}

Angle CircularMeanOfSums(double sum_x, double sum_y, bool* defined) {
  // hypot(sum_x, sum_y) >= kUndefinedMeanLength, decided without hypot where the squared length
  // is clearly on one side (its rounding error is far below the 1e-9 margin, hypot within an
  // ulp; an underflowed square is below either way); NaN and the narrow band call hypot.
  const double squared = sum_x * sum_x + sum_y * sum_y;
  const double limit = kUndefinedMeanLength * kUndefinedMeanLength;
  bool is_defined = false;
  if (squared > limit * (1.0 + 1e-9)) {
    is_defined = true;
  } else if (squared < limit * (1.0 - 1e-9)) {
    is_defined = false;
  } else {
    is_defined = std::hypot(sum_x, sum_y) >= kUndefinedMeanLength;
  }
  if (defined != nullptr) *defined = is_defined;
  if (!is_defined) return Angle(0.0);
  return Angle::FromRadians(std::atan2(sum_y, sum_x));
}

}  // namespace core
}  // namespace swarm_transport
