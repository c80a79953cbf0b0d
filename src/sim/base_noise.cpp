#include "swarm_transport/sim/base_noise.h"

#include <cmath>
#include <sstream>

namespace swarm_transport {
namespace sim {
namespace {

// Streams of the seed's generator apart from the robots' (their id) and the radio's.
constexpr std::uint64_t kBaseNoiseStream = 0x62617365ULL << 16;  // "base"

bool NonNegative(double v) { return std::isfinite(v) && v >= 0.0; }

}  // namespace

std::string BaseNoiseParams::Validate() const {
  std::ostringstream os;
  if (!NonNegative(position_noise_m) || position_noise_m > 1.0) {
    os << "~position_noise_m must be a deviation in [0, 1] m but is " << position_noise_m;
  } else if (!NonNegative(heading_noise_deg) || heading_noise_deg > 180.0) {
    os << "~heading_noise_deg must be a deviation in [0, 180] degrees but is " << heading_noise_deg;
  } else if (!NonNegative(heading_drift_deg) || heading_drift_deg > 180.0) {
    os << "~heading_drift_deg must be a deviation in [0, 180] degrees per tick but is "
       << heading_drift_deg;
  }
  return os.str();
}

double Gaussian(core::Rng* rng) {
  // 1 - U in (0, 1]: the logarithm stays finite.
  const double u1 = 1.0 - rng->Uniform(0.0, 1.0);
  const double u2 = rng->Uniform(0.0, 1.0);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * M_PI * u2);
}

BaseNoise::BaseNoise(const BaseNoiseParams& params, std::uint64_t seed, std::uint16_t id)
    : params_(params), rng_(seed, kBaseNoiseStream + id) {}

core::Pose2 BaseNoise::Measure(const core::Pose2& truth) {
  core::Pose2 out = truth;
  if (params_.position_noise_m > 0.0) {
    out.position.x += params_.position_noise_m * Gaussian(&rng_);
    out.position.y += params_.position_noise_m * Gaussian(&rng_);
  }
  if (params_.heading_noise_deg > 0.0) {
    out.heading =
        core::Angle(truth.heading.degrees() + params_.heading_noise_deg * Gaussian(&rng_));
  }
  return out;
}

core::Angle BaseNoise::Drift(core::Angle heading) {
  if (params_.heading_drift_deg <= 0.0) return heading;
  return core::Angle(heading.degrees() + params_.heading_drift_deg * Gaussian(&rng_));
}

}  // namespace sim
}  // namespace swarm_transport
