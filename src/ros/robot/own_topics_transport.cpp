#include "swarm_transport/ros/robot/own_topics_transport.h"

#include <ros/callback_queue.h>
#include <std_msgs/String.h>

#include <chrono>

#include "swarm_transport/ros/common/graph.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

// Neighbors: one message per tick; a robot is never more than one tick behind.
constexpr std::uint32_t kNeighborsQueue = 2;
// Its own loop: rounds kept for its next tick (one per period arrives; more only when it was
// held up, and then the oldest are stale - its diagnostics count them missed).
constexpr std::size_t kRoundsKept = 4;
constexpr std::uint32_t kStatsQueue = 10;
// AwaitDispatcher: how long a robot stays quiet at most, and how often it asks the master.
constexpr double kDispatcherWaitS = 10.0;
constexpr double kDispatcherPollS = 0.2;

}  // namespace

void OwnTopicsTransport::Prepare(ros::NodeHandle* nh, ros::NodeHandle* private_nh) {
  if (!realtime()) return;
  // Before anything is connected: every callback of its handles runs under its lock.
  locked_queue_ = std::make_unique<LockedCallbackQueue>(ros::getGlobalCallbackQueue(), &mutex_);
  nh->setCallbackQueue(locked_queue_.get());
  private_nh->setCallbackQueue(locked_queue_.get());
}

void OwnTopicsTransport::Connect(ros::NodeHandle nh, const TransportOptions& link,
                                 RobotInbox* robot) {
  robot_ = robot;
  id_ = link.id;
  // tcpNoDelay: a tick's perception is one small message; Nagle would add ~40 ms per tick.
  if (realtime()) {
    cmd_pub_ = nh.advertise<geometry_msgs::Twist>(names::kCmdVel, 2);
    // Lock-step: mission messages arrive relayed inside its rounds, each at the tick after it
    // was sent, and go out inside its answers: no mission topics, nothing to connect.
    mission_topics_.Subscribe(
        nh, [robot](const core::MissionMessage& message, const core::Sender& from) {
          robot->Hand(message, from);
        });
    AwaitDispatcher(nh);
  } else {
    answer_pub_ = nh.advertise<Tick_Answer>(names::kAnswer, 2);
    neighbors_sub_ = nh.subscribe<Neighbors>(
        names::kNeighbors, kNeighborsQueue,
        boost::function<void(const Neighbors::ConstPtr&)>([robot](const Neighbors::ConstPtr& msg) {
          robot->TakeRound(msg, ros::WallTime::now().toSec());
        }),
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  }
  robots_sub_ = nh.subscribe<Robot_Positions>(
      names::kRobots, 2,
      boost::function<void(const Robot_Positions::ConstPtr&)>(
          [robot](const Robot_Positions::ConstPtr& msg) { robot->HearRobots(*msg); }));
  if (link.diagnostics)
    stats_pub_ = nh.advertise<std_msgs::String>(names::kRobotStats, kStatsQueue);
}

void OwnTopicsTransport::AwaitDispatcher(ros::NodeHandle nh) {
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(kDispatcherWaitS);
  const auto ready = [this, until, nh]() {
    TopicNodeCounts graph;
    const bool connected =
        QueryTopicNodeCounts(&graph) &&
        mission_topics_.AllConnected(graph, {names::kMissionNew, names::kMissionEvent});
    if (!connected && ros::WallTime::now() < until) return false;
    if (!connected) {
      ROS_WARN(
          "robot %u: the dispatcher's topics are not connected after %.0f s; joining the "
          "radio all the same (an order sent meanwhile may have missed it)",
          id_, kDispatcherWaitS);
    }
    SubscribeNeighbors(nh);
    return true;
  };
  if (ready()) return;
  dispatcher_wait_ = nh.createWallTimer(ros::WallDuration(kDispatcherPollS),
                                        [this, ready](const ros::WallTimerEvent&) {
                                          if (!neighbors_sub_ && ready()) dispatcher_wait_.stop();
                                        });
}

void OwnTopicsTransport::SubscribeNeighbors(ros::NodeHandle nh) {
  // Put into its mailbox by roscpp's receiving thread; taken at its next tick (OnTickDue).
  ros::SubscribeOptions ops = ros::SubscribeOptions::create<Neighbors>(
      names::kNeighbors, kNeighborsQueue,
      [this](const Neighbors::ConstPtr& msg) {
        mailbox_.Put(msg, ros::WallTime::now().toSec(), kRoundsKept);
      },
      ros::VoidConstPtr(), &inline_queue_);
  ops.transport_hints = ros::TransportHints().tcpNoDelay();
  neighbors_sub_ = nh.subscribe(ops);
}

void OwnTopicsTransport::Disconnect() {
  dispatcher_wait_.stop();
  ticker_.Stop();
  neighbors_sub_.shutdown();
  mission_topics_.Shutdown();
  robots_sub_.shutdown();
}

void OwnTopicsTransport::SendCommand(const geometry_msgs::Twist& command) {
  if (cmd_pub_) cmd_pub_.publish(command);
}

void OwnTopicsTransport::SendStats(const std::string& line) {
  std_msgs::String msg;
  msg.data = line;
  stats_pub_.publish(msg);
}

bool OwnTopicsTransport::Spin(double tick_period_s) {
  if (!realtime()) {
    ros::spin();
    return true;
  }
  return SpinWithOwnTicks(
      &ticker_, tick_period_s, [this] { OnTickDue(); }, id_);
}

void OwnTopicsTransport::OnTickDue() {
  std::lock_guard<std::mutex> lock(mutex_);
  // Take in what arrived, compute one action and execute it.
  mailbox_.TakeAll(&arrived_);
  for (const RoundMailbox::Arrived& a : arrived_) robot_->TakeRound(a.round, a.wall_s);
  arrived_.clear();
  robot_->TimerTick();
}

}  // namespace swarm_transport
