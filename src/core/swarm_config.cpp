#include "swarm_transport/core/swarm_config.h"

#include <cmath>
#include <sstream>
#include <utility>

namespace swarm_transport {
namespace core {

FlockingTuning FlockingTuning::Of(const FlockingParams& flocking) {
  FlockingTuning t;
  t.free_will_deg = flocking.free_will_deg;
  t.cohesion = flocking.cohesion;
  t.local_range_m = flocking.local_range_m;
  t.speed_m_per_tick = flocking.speed_m_per_tick;
  return t;
}

std::string SwarmConfig::Retune(const FlockingTuning& tuning) {
  SwarmConfig tuned = *this;
  tuned.flocking.free_will_deg = tuning.free_will_deg;
  tuned.flocking.cohesion = tuning.cohesion;
  tuned.flocking.local_range_m = tuning.local_range_m;
  tuned.flocking.speed_m_per_tick = tuning.speed_m_per_tick;
  std::string why = tuned.Validate();
  if (why.empty()) *this = std::move(tuned);
  return why;
}

std::string SwarmConfig::Validate() const {
  std::string e = flocking.Validate();
  if (!e.empty()) return e;
  e = leader.Validate();
  if (!e.empty()) return e;
  e = transport.Validate();
  if (!e.empty()) return e;
  e = balloon.Validate();
  if (!e.empty()) return e;
  std::ostringstream os;
  if (!(tick_period_s > 0.0) || !std::isfinite(tick_period_s)) {
    os << "tick_period_s must be > 0 but is " << tick_period_s;
  } else if (!std::isfinite(loaded_delay_s) || !std::isfinite(unloaded_delay_s)) {
    os << "loaded_delay_s and unloaded_delay_s must be finite";
  } else if (object_update_ticks < 1) {
    os << "object_update_ticks must be >= 1 but is " << object_update_ticks;
  } else if (chain_hops < 1) {
    os << "chain_hops must be >= 1 but is " << chain_hops;
  } else if (!std::isfinite(lost_after_s) || !(lost_after_s > 0.0)) {
    os << "lost_after_s must be > 0 (s) but is " << lost_after_s;
  } else if (mission_min_robots < 0 || mission_min_robots > 65535) {
    os << "mission_min_robots must be in [0, 65535] but is " << mission_min_robots;
  } else if (max_live_missions < 1 || max_live_missions > 65535) {
    os << "max_live_missions must be in [1, 65535] but is " << max_live_missions;
  } else if (loading_spread != LoadingSpread::kNone && loading_spread != LoadingSpread::kBalloon) {
    os << "loading_spread must be none or balloon but is " << static_cast<int>(loading_spread);
  } else if (loading_spread_ticks < 1 || loading_spread_ticks > 10000) {
    os << "loading_spread_ticks must be in [1, 10000] but is " << loading_spread_ticks;
  }
  return os.str();
}

}  // namespace core
}  // namespace swarm_transport
