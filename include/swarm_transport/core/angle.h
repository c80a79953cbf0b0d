// Angles in degrees, wrapped to [0, 360), as the thesis uses them [T5.2].
#ifndef SWARM_TRANSPORT_CORE_ANGLE_H_
#define SWARM_TRANSPORT_CORE_ANGLE_H_

#include <vector>

namespace swarm_transport {
namespace core {

// A heading in degrees, always wrapped to [0, 360): Angle(350) + Angle(20) == Angle(10).
class Angle {
 public:
  Angle() = default;
  explicit Angle(double degrees);
  static Angle FromRadians(double radians);

  double degrees() const { return degrees_; }
  double radians() const;

  Angle operator+(Angle other) const;
  Angle operator-(Angle other) const;
  // Equal within 1e-9 degrees, treating 0 and 360 - epsilon as equal.
  bool operator==(Angle other) const;
  bool operator!=(Angle other) const { return !(*this == other); }

  // Signed shortest difference `to - from` in degrees, in (-180, 180].
  static double SignedDifference(Angle to, Angle from);

 private:
  double degrees_ = 0.0;
};

// Circular mean: sum of unit vectors, atan2. When the vectors cancel (|sum| < 1e-9) the mean
// is undefined: `defined` is set false and Angle(0) returned [T5.2: 45 and 315 -> 0; 0 and
// 180 cancel]. `weights` may be empty (all 1) or the same size as `angles`.
Angle CircularMean(const std::vector<Angle>& angles, bool* defined,
                   const std::vector<double>& weights = {});
// CircularMean from its summed unit vectors (sum of weight * cos, of weight * sin).
Angle CircularMeanOfSums(double sum_x, double sum_y, bool* defined);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_ANGLE_H_
