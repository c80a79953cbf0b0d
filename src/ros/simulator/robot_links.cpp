#include "swarm_transport/ros/simulator/robot_links.h"

#include <algorithm>
#include <utility>

#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

// Queue sizes. Neighbors: one message per tick, a robot is never more than one tick behind.
// cmd_vel: lock-step sends one per tick; real time may burst. Answers: one per robot and tick;
// late ones may queue behind the current one.
constexpr std::uint32_t kNeighborsQueue = 2;
constexpr std::uint32_t kPoseQueue = 10;
constexpr std::uint32_t kCmdVelQueue = 10;
constexpr std::uint32_t kAnswerQueue = 10;

}  // namespace

void RobotLink::Deliver(std::uint16_t id, DirectRobots* direct_robots, Neighbors&& round) {
  if (direct) {
    direct_robots->Deliver(id, boost::make_shared<const Neighbors>(std::move(round)));
  } else {
    neighbors.publish(round);
  }
}

void RobotLink::Shutdown() {
  neighbors.shutdown();
  pose.shutdown();
  cmd_vel.shutdown();
  answer.shutdown();
  teleport_absolute.shutdown();
  teleport_relative.shutdown();
}

RobotLinks::RobotLinks(ros::NodeHandle nh, ros::CallbackQueue* command_queue, DirectRobots* direct,
                       bool lockstep, bool pose_topics, RobotLinkHandlers handlers)
    : nh_(nh),
      command_queue_(command_queue),
      direct_(direct),
      lockstep_(lockstep),
      pose_topics_(pose_topics),
      handlers_(std::move(handlers)) {}

void RobotLinks::Add(std::uint16_t id) {
  ros::NodeHandle robot_nh(nh_, names::RobotNamespace(id));
  RobotLink link;
  link.generation = ++next_generation_;
  const std::uint64_t generation = link.generation;
  // Status callbacks run on the global queue, i.e. from the simulator's loop like everything.
  auto counter = [this, id, generation](int RobotLink::*field, int delta) {
    return [this, id, generation, field, delta](const ros::SingleSubscriberPublisher&) {
      CountSubscriber(id, generation, field, delta);
    };
  };
  if (pose_topics_) {
    link.pose =
        robot_nh.advertise<Pose>(names::kPose, kPoseQueue, counter(&RobotLink::pose_subscribers, 1),
                                 counter(&RobotLink::pose_subscribers, -1));
  }
  // A robot of this process linked directly: its round, command and answer bypass roscpp.
  link.direct = direct_ != nullptr && direct_->Hosts(id);
  if (!link.direct) {
    link.neighbors = robot_nh.advertise<Neighbors>(names::kNeighbors, kNeighborsQueue,
                                                   counter(&RobotLink::neighbors_subscribers, 1),
                                                   counter(&RobotLink::neighbors_subscribers, -1));
    ros::SubscribeOptions ops = ros::SubscribeOptions::create<geometry_msgs::Twist>(
        names::kCmdVel, kCmdVelQueue,
        [this, id](const geometry_msgs::Twist::ConstPtr& msg) { handlers_.cmd_vel(id, *msg); },
        ros::VoidConstPtr(), command_queue_);
    // A tick's command is one small message: Nagle's algorithm would delay it by ~40 ms.
    ops.transport_hints = ros::TransportHints().tcpNoDelay();
    link.cmd_vel = robot_nh.subscribe(ops);
    if (lockstep_) {
      ros::SubscribeOptions answer_ops = ros::SubscribeOptions::create<Tick_Answer>(
          names::kAnswer, kAnswerQueue,
          [this, id](const Tick_Answer::ConstPtr& msg) { handlers_.answer(id, *msg); },
          ros::VoidConstPtr(), command_queue_);
      answer_ops.transport_hints = ros::TransportHints().tcpNoDelay();
      link.answer = robot_nh.subscribe(answer_ops);
    }
  }
  // Every robot's teleports, unless the process hosting it directly asks for none (a
  // robot_host with ~robot_services false: registering them is O(N^2) in roscpp and the master).
  if (!link.direct || direct_->RobotServices()) {
    AdvertiseTeleports(id, robot_nh, &link);
  }
  links_[id] = link;
}

void RobotLinks::AdvertiseTeleports(std::uint16_t id, ros::NodeHandle& robot_nh, RobotLink* out) {
  RobotLink& link = *out;
  link.teleport_absolute =
      robot_nh.advertiseService<TeleportAbsolute::Request, TeleportAbsolute::Response>(
          names::kTeleportAbsolute,
          [this, id](TeleportAbsolute::Request& req, TeleportAbsolute::Response& res) {
            return handlers_.teleport_absolute(id, req, res);
          });
  link.teleport_relative =
      robot_nh.advertiseService<TeleportRelative::Request, TeleportRelative::Response>(
          names::kTeleportRelative,
          [this, id](TeleportRelative::Request& req, TeleportRelative::Response& res) {
            return handlers_.teleport_relative(id, req, res);
          });
}

void RobotLinks::Remove(std::uint16_t id) {
  auto it = links_.find(id);
  if (it == links_.end()) return;
  it->second.Shutdown();
  links_.erase(it);
}

void RobotLinks::Shutdown() {
  for (auto& entry : links_) entry.second.Shutdown();
  links_.clear();
}

RobotLink* RobotLinks::Find(std::uint16_t id) {
  auto it = links_.find(id);
  return it == links_.end() ? nullptr : &it->second;
}

bool RobotLinks::Ready(RobotLink* link, double settle_s) {
  // Nothing to connect: a direct robot hears its first round and answers it for sure.
  if (link->direct) return true;
  // Only checked until the robot is live: getNumPublishers() scans every subscription.
  const bool connected =
      link->neighbors_subscribers > 0 && link->answer && link->answer.getNumPublishers() > 0;
  const ros::WallTime now = ros::WallTime::now();
  if (!connected) {
    link->connected_since = ros::WallTime();
  } else if (link->connected_since.isZero()) {
    link->connected_since = now;
  }
  return connected && (now - link->connected_since).toSec() >= settle_s;
}

void RobotLinks::CountSubscriber(std::uint16_t id, std::uint64_t generation, int RobotLink::*field,
                                 int delta) {
  auto it = links_.find(id);
  if (it == links_.end() || it->second.generation != generation) return;
  it->second.*field = std::max(0, it->second.*field + delta);
}

}  // namespace swarm_transport
