// The stand-in for real hardware (swarm.launch deploy:=hardware, docs/hardware.md): each robot is
// a kinematic base - the simulator's World2D, without rounds, radio or lock-step - that takes
// robot_<id>/cmd_vel and reports robot_<id>/odom (nav_msgs/Odometry) and tf
// <prefix><id>/odom -> <prefix><id>/base_link at its own rate, with Gaussian odometry noise and
// a heading drift of its own. The robots on top are hardware robots (hardware_transport.h). For
// the dispatcher, the recorder and the tools it publishes what the simulator would: the bases'
// true poses on /flock/world_poses once per tick and the robot list on /flock/robots.
#ifndef SWARM_TRANSPORT_ROS_BASES_BASES_H_
#define SWARM_TRANSPORT_ROS_BASES_BASES_H_

#include <geometry_msgs/Twist.h>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>
#include <tf2_ros/transform_broadcaster.h>

#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "swarm_transport/core/modes.h"
#include "swarm_transport/ros/common/event_schedule.h"
#include "swarm_transport/ros/common/mission_topics.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/sim/base_noise.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {

// The stand-in's parameters (private ones with ~, the rest from /swarm).
struct BasesParams {
  SwarmConfig swarm;
  int robots = 0;  // ~robots: bases 0..N-1, [0, 65535]
  core::Placement placement = core::Placement::kRandom;
  std::string placement_file;
  double odom_rate_hz = 50.0;  // ~odom_rate_hz: odometry and tf per wall second, (0, 1000]
  double integration_step_s = 0.01;
  sim::BaseNoiseParams noise;           // ~position_noise_m, ~heading_noise_deg, ...
  std::string frame_prefix = "robot_";  // ~frame_prefix: frames <prefix><id>/odom, /base_link
  std::string fixed_frame = "map";      // ~fixed_frame: the shared frame, = every odom frame
  bool tf = true;                       // ~tf
  std::string events_file;              // ~events_file: odom_stop, freeze, continue
  // ~positions: publish the true poses on /flock/world_poses and the list on /flock/robots
  // (false: the core machine's positions node does, from the robots' /flock/position).
  bool positions = true;
  std::string Validate() const;
};
bool ReadBasesParams(const ros::NodeHandle& nh, const ros::NodeHandle& p, BasesParams* params,
                     std::string* error);

class Bases {
 public:
  Bases(ros::NodeHandle nh, ros::NodeHandle private_nh) : nh_(nh), private_nh_(private_nh) {}
  // Reads and checks its parameters, places the bases; false (after one ROS_FATAL) on bad input.
  bool Initialize();
  // Drives the bases until ROS shuts down.
  void Run();

 private:
  void OnCmdVel(std::uint16_t id, const geometry_msgs::Twist& msg);
  // A tick begins: contacts, events, the heading drift, /flock/world_poses.
  void BeginTick(double since_start_s);
  void PublishOdometry();
  std::string Frame(std::uint16_t id, const char* frame) const;

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  BasesParams params_;
  std::unique_ptr<sim::World2D> world_;
  std::map<std::uint16_t, sim::BaseNoise> noise_;
  std::map<std::uint16_t, std::uint64_t> silent_until_;  // odom_stop: no odometry before this tick
  std::vector<TimedEvent> events_;
  std::unique_ptr<EventSchedule> schedule_;
  std::uint64_t tick_ = 0;
  std::vector<ros::Subscriber> cmd_subs_;
  std::map<std::uint16_t, ros::Publisher> odom_pubs_;
  ros::Publisher positions_pub_;
  ros::Publisher robots_pub_;
  MissionPublishers mission_pubs_;  // freeze and continue of the event schedule
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_;
  std::unique_ptr<tf2_ros::StaticTransformBroadcaster> static_tf_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_BASES_BASES_H_
