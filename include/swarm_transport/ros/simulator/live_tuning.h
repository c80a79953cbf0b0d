// The simulator's live flocking tuning (issue 13): the relay that carries an accepted change to
// every robot with the next round, its dynamic_reconfigure server and the latched /flock/tuning.
#ifndef SWARM_TRANSPORT_ROS_LIVE_TUNING_H_
#define SWARM_TRANSPORT_ROS_LIVE_TUNING_H_

#include <ros/ros.h>

#include <cstdint>
#include <memory>
#include <optional>

#include "swarm_transport/Flocking_Tuning.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/core/swarm_config.h"
#include "swarm_transport/ros/simulator/flocking_tuning.h"
#include "swarm_transport/sim/mission_relay.h"

namespace swarm_transport {

// sim::TuningRelay + FlockingTuningServer + /flock/tuning, on the simulator's thread (global
// queue).
class LiveTuning {
 public:
  explicit LiveTuning(const core::SwarmConfig& swarm) : relay_(swarm) {}

  // Advertises /flock/tuning and starts the dynamic_reconfigure server on `private_nh`;
  // `radio_loss` is the loss the simulator's radio starts with.
  void Connect(ros::NodeHandle nh, ros::NodeHandle private_nh, double radio_loss);
  void Shutdown();

  // Round `tick` begins: a tuning accepted since the last round becomes current, goes out on
  // /flock/tuning and is returned (once).
  std::optional<core::TuningGeneration> BeginRound(std::uint64_t tick);
  // The current tuning into a robot's round (nothing before the first change).
  void Fill(core::Round* round) const { relay_.Fill(round); }
  std::uint32_t generation() const { return relay_.generation(); }
  // A radio loss accepted since the last call, once (for the simulator's radio).
  std::optional<double> TakeRadioLoss() {
    return server_ ? server_->TakeRadioLoss() : std::nullopt;
  }

 private:
  sim::TuningRelay relay_;
  std::unique_ptr<FlockingTuningServer> server_;
  ros::Publisher pub_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_LIVE_TUNING_H_
