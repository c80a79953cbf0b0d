#include "swarm_transport/ros/simulator/flocking_tuning.h"

#include <cmath>
#include <string>

namespace swarm_transport {

FlockingConfig ToFlockingConfig(const core::FlockingTuning& tuning, double radio_loss) {
  FlockingConfig config = FlockingConfig::__getDefault__();
  config.radio_loss = radio_loss;
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

FlockingTuningServer::FlockingTuningServer(ros::NodeHandle private_nh, sim::TuningRelay* relay,
                                           double radio_loss)
    : relay_(relay), radio_loss_(radio_loss) {
  // The server reads its first values from ~free_will_deg etc. (the .cfg's defaults when
  // unset): /swarm's values are put there first, so that it starts with what the swarm uses.
  const core::FlockingTuning start = relay_->newest();
  private_nh.setParam("free_will_deg", start.free_will_deg);
  private_nh.setParam("cohesion", start.cohesion);
  private_nh.setParam("local_range_m", start.local_range_m);
  private_nh.setParam("speed_m_per_tick", start.speed_m_per_tick);
  private_nh.setParam("radio_loss", radio_loss_);
  server_ = std::make_unique<dynamic_reconfigure::Server<FlockingConfig>>(mutex_, private_nh);
  server_->setCallback(
      [this](FlockingConfig& config, std::uint32_t level) { OnReconfigure(config, level); });
}

void FlockingTuningServer::OnReconfigure(FlockingConfig& config, std::uint32_t /*level*/) {
  const core::FlockingTuning wanted = ToFlockingTuning(config);
  const core::FlockingTuning before = relay_->newest();
  const double loss = config.radio_loss;
  // One change is taken whole or not at all: the radio's loss is checked before the relay
  // takes the flocking part.
  std::string why;
  if (!std::isfinite(loss) || loss < 0.0 || loss > 1.0) {
    why = "radio_loss must be a probability in [0, 1] but is " + std::to_string(loss);
  } else {
    why = relay_->Propose(wanted);
  }
  if (!why.empty()) {
    ROS_ERROR(
        "simulator: refused the flocking tuning (dynamic_reconfigure): %s; nothing changed "
        "(free_will_deg %g, cohesion %g, local_range_m %g, speed_m_per_tick %g, radio_loss %g)",
        why.c_str(), before.free_will_deg, before.cohesion, before.local_range_m,
        before.speed_m_per_tick, radio_loss_);
    // The server stores, publishes and answers what the callback leaves in `config`.
    config = ToFlockingConfig(before, radio_loss_);
    return;
  }
  if (loss != radio_loss_) {
    radio_loss_ = loss;
    pending_radio_loss_ = loss;
    ROS_INFO("simulator: radio loss %g accepted; the radio uses it from the next round", loss);
  }
  if (wanted == before) return;
  ROS_INFO(
      "simulator: flocking tuning accepted: free_will_deg %g, cohesion %g, local_range_m %g, "
      "speed_m_per_tick %g; every robot uses it from the next tick",
      wanted.free_will_deg, wanted.cohesion, wanted.local_range_m, wanted.speed_m_per_tick);
}

std::optional<double> FlockingTuningServer::TakeRadioLoss() {
  std::optional<double> taken;
  taken.swap(pending_radio_loss_);
  return taken;
}

}  // namespace swarm_transport
