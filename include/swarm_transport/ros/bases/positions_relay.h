// The core machine's view of a swarm on real robots (core.launch, docs/hardware.md): there is
// no simulator to publish every robot's pose, so this node gathers the robots' own
// /flock/position announcements and publishes them once per tick as /flock/world_poses (what the
// dispatcher, the recorder, rviz tools and tests read), and the robots it ever heard as the
// latched /flock/robots list.
#ifndef SWARM_TRANSPORT_ROS_BASES_POSITIONS_RELAY_H_
#define SWARM_TRANSPORT_ROS_BASES_POSITIONS_RELAY_H_

#include <ros/ros.h>

#include <cstdint>
#include <map>
#include <string>

#include "swarm_transport/Robot_Position.h"

namespace swarm_transport {

class PositionsRelay {
 public:
  PositionsRelay(ros::NodeHandle nh, ros::NodeHandle private_nh)
      : nh_(nh), private_nh_(private_nh) {}
  // Reads /swarm/tick_period_s and ~heard_timeout_s; false (after one ROS_FATAL) on bad input.
  bool Initialize();

 private:
  void OnPosition(const Robot_Position::ConstPtr& msg);
  void OnTick();

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  double tick_period_s_ = 0.1;
  double heard_timeout_s_ = 1.0;  // a robot silent this long is left out of /flock/world_poses
  struct Heard {
    Robot_Position position;
    double at_s = 0.0;
  };
  std::map<std::uint16_t, Heard> heard_;
  bool roster_changed_ = false;
  std::uint64_t tick_ = 0;
  ros::WallTime start_;
  ros::Subscriber position_sub_;
  ros::Publisher positions_pub_;
  ros::Publisher robots_pub_;
  ros::WallTimer timer_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_BASES_POSITIONS_RELAY_H_
