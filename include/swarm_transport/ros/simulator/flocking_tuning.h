// The simulator's dynamic_reconfigure server of the flocking parameters (issue 13): free will,
// cohesion, local range and speed of a running swarm (cfg/Flocking.cfg). It only validates and
// hands a change to the sim::TuningRelay (sim/mission_relay.h), which carries it to every robot.
#ifndef SWARM_TRANSPORT_ROS_FLOCKING_TUNING_H_
#define SWARM_TRANSPORT_ROS_FLOCKING_TUNING_H_

#include <dynamic_reconfigure/server.h>
#include <ros/ros.h>

#include <boost/thread/recursive_mutex.hpp>
#include <cstdint>
#include <memory>

#include "swarm_transport/FlockingConfig.h"
#include "swarm_transport/sim/mission_relay.h"

namespace swarm_transport {

// dynamic_reconfigure <-> sim::TuningRelay. At start the server holds /swarm's values (not the
// .cfg's defaults). A change that fails the robots' check is refused with one ROS_ERROR naming
// the key and the accepted range: the server keeps (and answers with) the values in use.
class FlockingTuningServer {
 public:
  // `relay` must outlive the server; its callbacks run on `private_nh`'s queue.
  FlockingTuningServer(ros::NodeHandle private_nh, sim::TuningRelay* relay);

 private:
  void OnReconfigure(FlockingConfig& config, std::uint32_t level);  // NOLINT: its signature

  sim::TuningRelay* relay_;
  boost::recursive_mutex mutex_;
  std::unique_ptr<dynamic_reconfigure::Server<FlockingConfig>> server_;
};

// The relay's values as the .cfg's config, and back.
FlockingConfig ToFlockingConfig(const core::FlockingTuning& tuning);
core::FlockingTuning ToFlockingTuning(const FlockingConfig& config);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_FLOCKING_TUNING_H_
