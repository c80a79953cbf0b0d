#include "swarm_transport/ros/simulator/flocking_tuning.h"

#include <string>

namespace swarm_transport {

FlockingConfig ToFlockingConfig(const core::FlockingTuning& tuning) {
  FlockingConfig config = FlockingConfig::__getDefault__();
  config.free_will_deg = tuning.free_will_deg;
  config.cohesion = tuning.cohesion;
  config.local_range_m = tuning.local_range_m;
  config.speed_m_per_tick = tuning.speed_m_per_tick;
  return config;
}

core::FlockingTuning ToFlockingTuning(const FlockingConfig& config) {
  core::FlockingTuning t;
  t.free_will_deg = config.free_will_deg;
  t.cohesion = config.cohesion;
  t.local_range_m = config.local_range_m;
  t.speed_m_per_tick = config.speed_m_per_tick;
  return t;
}

FlockingTuningServer::FlockingTuningServer(ros::NodeHandle private_nh, sim::TuningRelay* relay)
    : relay_(relay) {
  // The server reads its first values from ~free_will_deg etc. (the .cfg's defaults when
  // unset): /swarm's values are put there first, so that it starts with what the swarm uses.
  const core::FlockingTuning start = relay_->newest();
  private_nh.setParam("free_will_deg", start.free_will_deg);
  private_nh.setParam("cohesion", start.cohesion);
  private_nh.setParam("local_range_m", start.local_range_m);
  private_nh.setParam("speed_m_per_tick", start.speed_m_per_tick);
  server_ = std::make_unique<dynamic_reconfigure::Server<FlockingConfig>>(mutex_, private_nh);
  server_->setCallback(
      [this](FlockingConfig& config, std::uint32_t level) { OnReconfigure(config, level); });
}

void FlockingTuningServer::OnReconfigure(FlockingConfig& config, std::uint32_t /*level*/) {
  const core::FlockingTuning wanted = ToFlockingTuning(config);
  const core::FlockingTuning before = relay_->newest();
  const std::string why = relay_->Propose(wanted);
  if (!why.empty()) {
    ROS_ERROR(
        "simulator: refused the flocking tuning (dynamic_reconfigure): %s; nothing changed "
        "(free_will_deg %g, cohesion %g, local_range_m %g, speed_m_per_tick %g)",
        why.c_str(), before.free_will_deg, before.cohesion, before.local_range_m,
        before.speed_m_per_tick);
    // The server stores, publishes and answers what the callback leaves in `config`.
    config = ToFlockingConfig(before);
    return;
  }
  if (wanted == before) return;
  ROS_INFO(
      "simulator: flocking tuning accepted: free_will_deg %g, cohesion %g, local_range_m %g, "
      "speed_m_per_tick %g; every robot uses it from the next tick",
      wanted.free_will_deg, wanted.cohesion, wanted.local_range_m, wanted.speed_m_per_tick);
}

}  // namespace swarm_transport
