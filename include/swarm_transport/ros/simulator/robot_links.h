// The simulator's per-robot ROS side: for each robot its robot_<id>/neighbors and pose
// publishers, its cmd_vel and (lock-step) answer subscriptions and its teleport services - or,
// for a robot of the simulator's own process, its direct link.
#ifndef SWARM_TRANSPORT_ROS_ROBOT_LINKS_H_
#define SWARM_TRANSPORT_ROS_ROBOT_LINKS_H_

#include <geometry_msgs/Twist.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <boost/container/flat_map.hpp>
#include <cstdint>
#include <functional>

#include "swarm_transport/Neighbors.h"
#include "swarm_transport/Pose.h"
#include "swarm_transport/TeleportAbsolute.h"
#include "swarm_transport/TeleportRelative.h"
#include "swarm_transport/Tick_Answer.h"
#include "swarm_transport/ros/common/direct_link.h"

namespace swarm_transport {

// The ROS side of one robot (or its direct link); its lock-step bookkeeping is the barrier's.
struct RobotLink {
  bool direct = false;  // linked directly: no neighbors, cmd_vel or answer topics
  ros::Publisher neighbors;
  ros::Publisher pose;
  ros::Subscriber cmd_vel;
  ros::Subscriber answer;  // lock-step: its Tick_Answer
  ros::ServiceServer teleport_absolute;
  ros::ServiceServer teleport_relative;
  // Connected subscribers, counted by connect / disconnect callbacks: getNumSubscribers()
  // scans every publication of the node, O(robots) per call.
  int neighbors_subscribers = 0;
  int pose_subscribers = 0;
  std::uint64_t generation = 0;   // tells this robot's callbacks from a killed namesake's
  ros::WallTime connected_since;  // lock-step: both links up since (zero: not connected)
  // Lock-step: it let a tick time out and is out of the barrier until it answers again (a hung
  // robot costs the tick timeout once, not every tick; issue 11).
  bool silent = false;

  // Hears its rounds: a direct link, or a process subscribed to its neighbors.
  bool Listening() const { return direct || neighbors_subscribers > 0; }
  // Hands it its round (by its direct link or on its topic).
  void Deliver(std::uint16_t id, DirectRobots* direct_robots, Neighbors&& round);
  void Shutdown();
};

// Where the links' callbacks go (the simulator's handlers). Commands and answers arrive on the
// queue given to RobotLinks (the simulator's command queue), services on the global one.
struct RobotLinkHandlers {
  std::function<void(std::uint16_t, const geometry_msgs::Twist&)> cmd_vel;
  std::function<void(std::uint16_t, const Tick_Answer&)> answer;
  std::function<bool(std::uint16_t, TeleportAbsolute::Request&, TeleportAbsolute::Response&)>
      teleport_absolute;
  std::function<bool(std::uint16_t, TeleportRelative::Request&, TeleportRelative::Response&)>
      teleport_relative;
};

class RobotLinks {
 public:
  // Sorted by id in one array: found and walked for every robot in every round.
  using Map = boost::container::flat_map<std::uint16_t, RobotLink>;

  // `direct`: the robots of this process linked directly (may be null); `pose_topics`:
  // advertise robot_<id>/pose.
  RobotLinks(ros::NodeHandle nh, ros::CallbackQueue* command_queue, DirectRobots* direct,
             bool lockstep, bool pose_topics, RobotLinkHandlers handlers);

  // Connects robot `id` (a former link of the same id is replaced).
  void Add(std::uint16_t id);
  void Remove(std::uint16_t id);
  void Shutdown();
  RobotLink* Find(std::uint16_t id);
  Map::iterator begin() { return links_.begin(); }
  Map::iterator end() { return links_.end(); }
  Map::const_iterator begin() const { return links_.begin(); }
  Map::const_iterator end() const { return links_.end(); }
  std::size_t size() const { return links_.size(); }

  // Lock-step: the robot has listened to its neighbors and published its answers for
  // `settle_s` of wall time (a link counts before its handshake is done, and a command sent in
  // that window would be lost). A direct robot is always ready.
  static bool Ready(RobotLink* link, double settle_s);

 private:
  void AdvertiseTeleports(std::uint16_t id, ros::NodeHandle& robot_nh, RobotLink* link);
  void CountSubscriber(std::uint16_t id, std::uint64_t generation, int RobotLink::*field,
                       int delta);

  ros::NodeHandle nh_;
  ros::CallbackQueue* command_queue_;
  DirectRobots* direct_;
  bool lockstep_;
  bool pose_topics_;
  RobotLinkHandlers handlers_;
  Map links_;
  std::uint64_t next_generation_ = 0;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_ROBOT_LINKS_H_
