// The simulator's dynamic_reconfigure server of the flocking parameters (issue 13): free will,
// cohesion, local range and speed of a running swarm (cfg/Flocking.cfg). It only validates and
// hands a change to the sim::TuningRelay (sim/mission_relay.h), which carries it to every robot.
// It also serves the simulator's own radio loss (not relayed: the simulator's radio takes it).
#ifndef SWARM_TRANSPORT_ROS_FLOCKING_TUNING_H_
#define SWARM_TRANSPORT_ROS_FLOCKING_TUNING_H_

#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>

#include <boost/thread/recursive_mutex.hpp>
#include <cstdint>
#include <memory>
#include <optional>

#include "swarm_transport/FlockingConfig.h"
#include "swarm_transport/sim/mission_relay.h"

namespace swarm_transport {

// dynamic_reconfigure <-> sim::TuningRelay. At start the server holds /swarm's values (not the
// .cfg's defaults). A change that fails the robots' check is refused with one ROS_ERROR naming
// the key and the accepted range: the server keeps (and answers with) the values in use.
class FlockingTuningServer {
 public:
  // `relay` must outlive the server; its callbacks run on `private_nh`'s queue. `radio_loss`:
  // the loss the simulator's radio starts with (/swarm/radio_loss).
  FlockingTuningServer(ros::NodeHandle private_nh, sim::TuningRelay* relay, double radio_loss);

  // A radio loss accepted since the last call, once (nothing when unchanged).
  std::optional<double> TakeRadioLoss();

 private:
  void OnReconfigure(FlockingConfig& config, std::uint32_t level);  // NOLINT: its signature

  sim::TuningRelay* relay_;
  double radio_loss_;                         // the accepted loss
  std::optional<double> pending_radio_loss_;  // accepted, not yet taken by the radio
  boost::recursive_mutex mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<FlockingConfig>> server_;
};

// The relay's values (and the radio's loss) as the .cfg's config, and back.
FlockingConfig ToFlockingConfig(const core::FlockingTuning& tuning, double radio_loss);
core::FlockingTuning ToFlockingTuning(const FlockingConfig& config);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_FLOCKING_TUNING_H_
