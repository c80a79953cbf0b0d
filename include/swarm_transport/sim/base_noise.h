// The hardware stand-in's imperfect bases (the `bases` node, docs/hardware.md): Gaussian noise
// on the odometry a base reports, and a heading drift of the base itself each tick (its wheels
// slip: it ends a tick turned a little from where it was told). Pure: no ROS, no clock; the
// same seed gives the same noise.
#ifndef SWARM_TRANSPORT_SIM_BASE_NOISE_H_
#define SWARM_TRANSPORT_SIM_BASE_NOISE_H_

#include <cstdint>
#include <string>

#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/random.h"

namespace swarm_transport {
namespace sim {

struct BaseNoiseParams {
  double position_noise_m = 0.0;   // σ of the reported x and y (each), m
  double heading_noise_deg = 0.0;  // σ of the reported heading, degrees
  double heading_drift_deg = 0.0;  // σ of the base's own heading change per tick, degrees
  // Empty when valid, else one sentence naming the first bad parameter and its range.
  std::string Validate() const;
  bool Any() const {
    return position_noise_m > 0.0 || heading_noise_deg > 0.0 || heading_drift_deg > 0.0;
  }
};

// A standard normal draw (Box-Muller) from `rng`.
double Gaussian(core::Rng* rng);

class BaseNoise {
 public:
  // Base `id`'s noise; its draws are the stream (seed, `id` + kBaseNoiseStream).
  BaseNoise(const BaseNoiseParams& params, std::uint64_t seed, std::uint16_t id);
  // What the base reports for its true pose `truth`.
  core::Pose2 Measure(const core::Pose2& truth);
  // The base's heading after one tick's drift.
  core::Angle Drift(core::Angle heading);

 private:
  BaseNoiseParams params_;
  core::Rng rng_;
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_BASE_NOISE_H_
