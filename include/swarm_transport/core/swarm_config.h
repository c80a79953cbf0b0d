// The shared swarm configuration (the /swarm keys of config/*.yaml), typed and validated in the
// core: every node and the robot brain take the same struct. ros/common/params.h loads it.
#ifndef SWARM_TRANSPORT_CORE_SWARM_CONFIG_H_
#define SWARM_TRANSPORT_CORE_SWARM_CONFIG_H_

#include <cstdint>
#include <string>
#include <vector>

#include "swarm_transport/core/balloon.h"
#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/leader.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/transport.h"

namespace swarm_transport {
namespace core {

// The flocking parameters a running swarm may change (dynamic_reconfigure, issue 13): free will,
// cohesion, local range and speed, as in FlockingParams.
struct FlockingTuning {
  double free_will_deg = 90.0;
  double cohesion = 0.0;
  double local_range_m = 1.0;
  double speed_m_per_tick = 0.1;

  static FlockingTuning Of(const FlockingParams& flocking);
  bool operator==(const FlockingTuning& o) const {
    return free_will_deg == o.free_will_deg && cohesion == o.cohesion &&
           local_range_m == o.local_range_m && speed_m_per_tick == o.speed_m_per_tick;
  }
  bool operator!=(const FlockingTuning& o) const { return !(*this == o); }
};

// Everything in the shared /swarm namespace (config/*.yaml): behaviour, clock, zones.
struct SwarmConfig {
  FlockingParams flocking;
  LeaderParams leader;
  TransportParams transport;
  double tick_period_s = 0.1;      // one tick (lock-step: simulated; real time: wall)
  std::uint64_t seed = 1;          // base seed; each robot's generator is (seed, id)
  std::vector<Zone> danger_zones;  // static danger zones
  double loaded_delay_s = 2.0;     // dispatcher: LOADED this long after LOADING (<0: wait)
  double unloaded_delay_s = 2.0;   // dispatcher: UNLOADED this long after UNLOADING
  int object_update_ticks = 1;     // a first leader publishes an object update every N ticks
  // The radio passes positions on hop by hop this many hops for a chain neighbourhood (1: only
  // robots in range are heard; mission peers are always heard over the mission channel).
  int chain_hops = 16;
  // A mission robot not heard for this long (s) is lost for its mission (SPEC 9.7): dropped, a
  // lost leader replaced by the next assigned robot. At least one tick.
  double lost_after_s = 0.5;
  // A running transport with fewer robots left than this ends ABORTED (SPEC 9.7; 0: its
  // leaders' number, the least it can run with).
  int mission_min_robots = 0;
  // Who admits mission orders (SPEC 9.7, issue 11): the dispatcher, or every robot itself when
  // no dispatcher runs (swarm.launch dispatcher:=false sets robots).
  Admission admission = Admission::kDispatcher;
  // At most this many live missions; more orders are REJECTED (dispatcher) or refused (robots).
  int max_live_missions = 64;
  // How a robot on no mission behaves (SPEC 9.5): flock (the default) or balloon dispersion.
  StandbyMode standby = StandbyMode::kFlock;
  BalloonParams balloon;  // balloon mode's growth
  // (ext, SPEC 9.5) How a transport mission's robots spend LOADING: none (frozen, the thesis)
  // or balloon (they spread under the object for loading_spread_ticks before the freeze).
  LoadingSpread loading_spread = LoadingSpread::kNone;
  int loading_spread_ticks = 10;

  // Empty when valid, else one sentence naming the bad key.
  std::string Validate() const;
  // Takes `tuning` over when the whole configuration stays valid (empty string); else nothing
  // changes and the sentence names the bad key.
  std::string Retune(const FlockingTuning& tuning);
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_SWARM_CONFIG_H_
