// The simulator's roster: which robots are in the world and how they join and leave - the
// /spawn, /kill and /reset services, each robot's teleports, New_Robot and Delete_Robot, the
// virtual copies and statists announced on /flock/position, and the latched /flock/robots.
#ifndef SWARM_TRANSPORT_ROS_ROBOT_ROSTER_H_
#define SWARM_TRANSPORT_ROS_ROBOT_ROSTER_H_

#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include <cstdint>
#include <string>

#include "swarm_transport/Delete_Robot.h"
#include "swarm_transport/Kill.h"
#include "swarm_transport/New_Robot.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/Spawn.h"
#include "swarm_transport/TeleportAbsolute.h"
#include "swarm_transport/TeleportRelative.h"
#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/random.h"
#include "swarm_transport/ros/common/direct_link.h"
#include "swarm_transport/ros/common/wall_throttle.h"
#include "swarm_transport/ros/simulator/lockstep_session.h"
#include "swarm_transport/ros/simulator/robot_links.h"
#include "swarm_transport/sim/mission_relay.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {

// Keeps the world's robots, their links, their places in the lock-step barrier and the robots
// of the simulator's own process in step. Runs on the simulator's thread (global queue).
class RobotRoster {
 public:
  // Everything given must outlive the roster; `session` is null in real time, `direct` when no
  // robot is linked directly; `tick` is the simulator's tick counter (stamps /flock/robots).
  RobotRoster(sim::World2D* world, RobotLinks* links, LockstepSession* session,
              DirectRobots* direct, std::uint64_t seed, const std::uint64_t* tick);

  void Connect(ros::NodeHandle nh, std::uint32_t position_queue, std::uint32_t queue);
  void Shutdown();

  // A robot of the world gets its links and (lock-step) its place in the barrier.
  void Add(std::uint16_t id);
  // Robot `id` leaves the world with its links and virtual copies (it must exist).
  void Remove(std::uint16_t id);
  // Spawns robot `id` at `pose` with its links; empty when done, else why not.
  std::string Spawn(std::uint16_t id, const core::Pose2& pose);
  // A scenario's timed kill of robot `id` (a warning when there is none).
  void KillByEvent(std::uint16_t id);
  // Latched /flock/robots: the robots that exist (robots check missions against it).
  void PublishList();

  bool OnTeleportAbsolute(std::uint16_t id, TeleportAbsolute::Request& req,
                          TeleportAbsolute::Response& res);
  bool OnTeleportRelative(std::uint16_t id, TeleportRelative::Request& req,
                          TeleportRelative::Response& res);

  // Virtual copies and statists, relayed by the radio.
  sim::RelayedPositions& relayed() { return relayed_; }
  const ros::Publisher& list_publisher() const { return robots_pub_; }

 private:
  bool OnSpawn(Spawn::Request& req, Spawn::Response& res);
  bool OnKill(Kill::Request& req, Kill::Response& res);
  bool OnReset(std_srvs::Empty::Request& req, std_srvs::Empty::Response& res);
  void OnPosition(const Robot_Position::ConstPtr& msg);
  // New_Robot of a physical robot: it joins at a free random pose (the /spawn service takes a
  // pose). Virtual copies and statists join by announcing themselves on /flock/position.
  void OnRobotNew(const New_Robot::ConstPtr& msg);
  // Delete_Robot: a virtual copy or statist of that (id, sub_id) is no longer relayed; else a
  // physical robot (sub_id 0) leaves the world, as by /kill.
  void OnRobotDelete(const Delete_Robot::ConstPtr& msg);

  sim::World2D* world_;
  RobotLinks* links_;
  LockstepSession* session_;
  DirectRobots* direct_;
  const std::uint64_t* tick_;
  core::Rng spawn_rng_;  // poses of robots that join by New_Robot
  sim::RelayedPositions relayed_;
  ros::Publisher robots_pub_;
  ros::ServiceServer spawn_srv_;
  ros::ServiceServer kill_srv_;
  ros::ServiceServer reset_srv_;
  ros::Subscriber position_sub_;
  ros::Subscriber robot_new_sub_;
  ros::Subscriber robot_delete_sub_;
  WarnThrottle bad_position_warning_;  // wall-clock throttles of repeated warnings
  WarnThrottle bad_delete_warning_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_ROBOT_ROSTER_H_
