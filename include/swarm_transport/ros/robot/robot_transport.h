// What carries one robot's messages: its radio rounds and the swarm's mission messages in, its
// answers out. A robot (RobotNode: its session and its tick) is the same in every deployment;
// the transport is what differs - its own topics (a robot process, own_topics_transport.h),
// its per-robot topics beside a host's shared subscriptions (host_transport.h) or a direct
// link to the simulator of its process (host_transport.h); on real hardware its base's pose, the
// other robots' positions over the network and its own radio (hardware_transport.h).
#ifndef SWARM_TRANSPORT_ROS_ROBOT_TRANSPORT_H_
#define SWARM_TRANSPORT_ROS_ROBOT_TRANSPORT_H_

#include <geometry_msgs/Twist.h>
#include <ros/ros.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "swarm_transport/Neighbors.h"
#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/Tick_Answer.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/core/modes.h"
#include "swarm_transport/core/swarm_config.h"

namespace swarm_transport {

// What a transport (or a host, for its shared subscriptions) hands a robot, always on the
// robot's thread.
class RobotInbox {
 public:
  virtual ~RobotInbox() = default;
  // A radio round that arrived at wall time `arrival_s`. Lock-step: one tick, answered.
  virtual void TakeRound(const Neighbors::ConstPtr& round, double arrival_s) = 0;
  // A mission message from `from` (real time: a mission topic's publisher).
  virtual void Hand(const core::MissionMessage& message, const core::Sender& from) = 0;
  // The simulator's robot list (/flock/robots).
  virtual void HearRobots(const Robot_Positions& list) = 0;
  // Real time: one tick on the latest round, due on the robot's own timeline.
  virtual void TimerTick() = 0;
  // A transport that is its own radio (hardware), before the round it hands next: of the robots
  // in that round, how many there are and how many were delivered in time (~diagnostics).
  virtual void CountDelivered(std::size_t /*expected*/, std::size_t /*delivered*/) {}
};

// The robot's parameters a transport needs to connect.
struct TransportOptions {
  std::uint16_t id = 0;
  core::Clock clock = core::Clock::kRealtime;
  bool diagnostics = false;  // it sends a line of figures per wall second (SendStats)
  const core::SwarmConfig* swarm = nullptr;  // /swarm as the robot uses it (outlives Connect)
};

class RobotTransport {
 public:
  virtual ~RobotTransport() = default;
  // Before the robot connects anything of its own: may give its handles another callback
  // queue.
  virtual void Prepare(ros::NodeHandle* /*nh*/, ros::NodeHandle* /*private_nh*/) {}
  // Connects its inputs on the robot's handle: from now on it hands `robot` what arrives.
  virtual void Connect(ros::NodeHandle nh, const TransportOptions& link, RobotInbox* robot) = 0;
  // Stops every input (each waits for its callback in progress).
  virtual void Disconnect() = 0;
  // Lock-step: the answer to a round (its command and everything it said).
  virtual void SendAnswer(const Tick_Answer& answer) = 0;
  // Real time: its command of this tick (mission messages go on the mission topics); also its
  // last zero command when it stops, in either clock.
  virtual void SendCommand(const geometry_msgs::Twist& command) = 0;
  // Its diagnostics line of this second.
  virtual void SendStats(const std::string& line) = 0;
  // Runs the robot until ROS shuts down; false (after one ROS_FATAL) when it cannot tick.
  virtual bool Spin(double /*tick_period_s*/) {
    ros::spin();
    return true;
  }
  // No tick of its own starts after it.
  virtual void Stop() {}
  // A process of its own: it stops when the swarm no longer lists it (a killed robot must not
  // act on; a re-spawned id gets a fresh process) and reports its status on /diagnostics. A
  // host removes its robots itself and reports once for all of them.
  virtual bool OwnProcess() const { return false; }
  // It announces its position on /flock/position every tick whoever listens (the other robots
  // on hardware hear it there), not only while an observer subscribes.
  virtual bool AnnouncesPosition() const { return false; }
  // It offers ~describe and ~state (a host of many robots may ask for none).
  virtual bool OffersServices() const { return true; }
  // Real time: how many nodes its cmd_vel reaches now (the simulator or its base: 1); -1 where
  // its commands take no topic of its own (lock-step, a robot host's direct link).
  virtual int CommandListeners() const { return -1; }
  // Real time: its commands go to the simulator, which turns a command's turn at once on receipt
  // (a round made before the last command arrived shows the pose before it: core::CommandEcho).
  // Not on hardware, where a base turns over time.
  virtual bool SimulatorTurnsOnReceipt() const { return false; }
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_ROBOT_TRANSPORT_H_
