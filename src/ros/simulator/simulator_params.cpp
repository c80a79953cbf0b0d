#include "swarm_transport/ros/simulator/simulator_params.h"

#include <cmath>
#include <sstream>

namespace swarm_transport {
namespace {

constexpr int kMaxRobots = 65536;
constexpr int kMaxTrailTicks = 10000;

}  // namespace

std::string SimulatorParams::Validate() const {
  std::ostringstream os;
  const std::string swarm_error = swarm.Validate();
  if (!swarm_error.empty()) {
    os << "/swarm: " << swarm_error;
  } else if (!std::isfinite(radio_loss) || radio_loss < 0.0 || radio_loss > 1.0) {
    os << "/swarm/radio_loss must be a probability in [0, 1] but is " << radio_loss;
  } else if (placement == core::Placement::kFile && placement_file.empty()) {
    os << "~placement_file must name a file when ~placement is file";
  } else if (robots > kMaxRobots || robots < (placement == core::Placement::kFile ? -1 : 0)) {
    os << "~robots must be in [0, " << kMaxRobots << "] but is " << robots;
  } else if (!std::isfinite(lockstep_timeout_s) || !(lockstep_timeout_s > 0.0)) {
    os << "~lockstep_timeout_s must be > 0 but is " << lockstep_timeout_s;
  } else if (lockstep_max_ticks < 0) {
    os << "~lockstep_max_ticks must be >= 0 (0: unbounded) but is " << lockstep_max_ticks;
  } else if (lockstep_observers < 0) {
    os << "~lockstep_observers must be >= 0 but is " << lockstep_observers;
  } else if (!std::isfinite(lockstep_start_timeout_s) || lockstep_start_timeout_s < 0.0) {
    os << "~lockstep_start_timeout_s must be >= 0 but is " << lockstep_start_timeout_s;
  } else if (!std::isfinite(real_time_factor) || real_time_factor < 0.0) {
    os << "~real_time_factor must be a finite number >= 0 (0: as fast as possible) but is "
       << real_time_factor;
  } else if (hold_at < 0) {
    os << "~hold_at must be >= 0 (0: no hold) but is " << hold_at;
  } else if (!std::isfinite(integration_step_s) || !(integration_step_s > 0.0) ||
             integration_step_s > swarm.tick_period_s) {
    os << "~integration_step_s must be in (0, tick_period_s = " << swarm.tick_period_s
       << "] but is " << integration_step_s;
  } else if (!std::isfinite(markers_rate_hz) || markers_rate_hz < 0.0) {
    os << "~markers_rate_hz must be >= 0 (0: off) but is " << markers_rate_hz;
  } else if (!std::isfinite(radio_range_m) || !(radio_range_m > 0.0)) {
    os << "~radio_range_m must be > 0 but is " << radio_range_m;
  } else if (trail_ticks < 0 || trail_ticks > kMaxTrailTicks) {
    os << "~trail_ticks must be in [0, " << kMaxTrailTicks << "] (0: off) but is " << trail_ticks;
  }
  return os.str();
}

bool ReadSimulatorParams(const ros::NodeHandle& nh, const ros::NodeHandle& p, bool direct,
                         SimulatorParams* params, std::string* error) {
  XmlRpc::XmlRpcValue swarm;
  if (nh.getParam("/swarm", swarm) && !ConfigFromXmlRpc(swarm, &params->swarm, error)) {
    *error = "/swarm: " + *error;
    return false;
  }
  if (nh.hasParam("/swarm/radio_loss") && !nh.getParam("/swarm/radio_loss", params->radio_loss)) {
    *error = "/swarm/radio_loss must be a number";
    return false;
  }
  params->radio_range_m = params->swarm.flocking.local_range_m;
  // Directly linked robots (a robot_host that runs the simulator) go without pose topics
  // unless asked for.
  params->pose_topics = !direct;
  if (!ReadPrivate(p, "placement", &params->placement, error)) return false;
  // With a placement file, robots defaults to every line of it.
  if (params->placement == core::Placement::kFile) params->robots = -1;
  if (!ReadPrivate(p, "robots", &params->robots, error) ||
      !ReadPrivate(p, "placement_file", &params->placement_file, error) ||
      !ReadPrivate(p, "events_file", &params->events_file, error) ||
      !ReadPrivate(p, "clock", &params->clock, error) ||
      !ReadPrivate(p, "lockstep_timeout_s", &params->lockstep_timeout_s, error) ||
      !ReadPrivate(p, "lockstep_max_ticks", &params->lockstep_max_ticks, error) ||
      !ReadPrivate(p, "lockstep_start_timeout_s", &params->lockstep_start_timeout_s, error) ||
      !ReadPrivate(p, "real_time_factor", &params->real_time_factor, error) ||
      !ReadPrivate(p, "hold_at", &params->hold_at, error) ||
      !ReadPrivate(p, "lockstep_observers", &params->lockstep_observers, error) ||
      !ReadPrivate(p, "lockstep_dispatcher", &params->lockstep_dispatcher, error) ||
      !ReadPrivate(p, "integration_step_s", &params->integration_step_s, error) ||
      !ReadPrivate(p, "markers_rate_hz", &params->markers_rate_hz, error) ||
      !ReadPrivate(p, "tf", &params->tf, error) ||
      !ReadPrivate(p, "range_circles", &params->range_circles, error) ||
      !ReadPrivate(p, "trail_ticks", &params->trail_ticks, error) ||
      !ReadPrivate(p, "radio_range_m", &params->radio_range_m, error) ||
      !ReadPrivate(p, "pose_topics", &params->pose_topics, error)) {
    return false;
  }
  *error = params->Validate();
  if (error->empty()) *error = WorldParamsOf(*params).Validate();
  return error->empty();
}

sim::WorldParams WorldParamsOf(const SimulatorParams& params) {
  sim::WorldParams world;
  world.world_size_m = params.swarm.flocking.world_size_m;
  world.robot_radius_m = params.swarm.flocking.robot_radius_m;
  world.integration_step_s = params.integration_step_s;
  // A command is one tick's move: it is held exactly one tick (turtlesim holds 1 s).
  world.command_duration_s = params.swarm.tick_period_s;
  return world;
}

sim::RadioParams RadioParamsOf(const SimulatorParams& params) {
  sim::RadioParams radio;
  radio.range_m = params.radio_range_m;
  radio.hops = params.swarm.flocking.neighbourhood == core::Neighbourhood::kChain
                   ? params.swarm.chain_hops
                   : 1;
  radio.loss = params.radio_loss;
  return radio;
}

}  // namespace swarm_transport
