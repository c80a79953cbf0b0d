// One robot of the swarm as a ROS node: its session (robot_session.h: brain, status sequencing,
// tuning), the transport that carries its messages (robot_transport.h: its own topics, a host's,
// or a direct link) and its tick.
#ifndef SWARM_TRANSPORT_ROS_ROBOT_NODE_H_
#define SWARM_TRANSPORT_ROS_ROBOT_NODE_H_

#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <string>

#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/Robot_State.h"
#include "swarm_transport/core/command_echo.h"
#include "swarm_transport/core/hardware.h"
#include "swarm_transport/core/modes.h"
#include "swarm_transport/core/robot_session.h"
#include "swarm_transport/ros/common/diagnostics.h"
#include "swarm_transport/ros/common/mission_resend.h"
#include "swarm_transport/ros/common/mission_topics.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/common/wall_throttle.h"
#include "swarm_transport/ros/robot/robot_stats.h"
#include "swarm_transport/ros/robot/robot_transport.h"

namespace swarm_transport {

// Private parameters of a robot node (the shared behaviour comes from /swarm).
struct RobotNodeOptions {
  int id = -1;  // ~id, required, [0, 65535]
  // ~clock: realtime (ticks on its own timeline every tick_period_s) or lockstep (tick per
  // Neighbors message from the simulator).
  core::Clock clock = core::Clock::kRealtime;
  // ~comm: local (flock on the radio's in-range list, SPEC 7) or broadcast (the thesis's
  // all-to-all wiring: flock on every robot's /flock/position; for comparison benchmarks).
  core::Comm comm = core::Comm::kLocal;
  // ~diagnostics: send tick timing and delivery figures on /flock/robot_stats once per wall
  // second (benchmarks; off by default).
  bool diagnostics = false;
  // ~hardware: a robot on real hardware (hardware_transport.h: its base's pose and cmd_vel, the
  // other robots over the network); real time and local comm only.
  bool hardware = false;
  std::string Validate() const;
};

// One robot of the swarm [SPEC 4]. In lock-step every round is one tick and is answered with
// exactly one Tick_Answer (its command and its mission messages); in real time it ticks every
// tick_period_s on its own timeline on the latest round (driven by its transport's loop or a
// host's worker), sends its command and, as a first leader, publishes the mission topics.
class RobotNode : public RobotInbox {
 public:
  RobotNode(ros::NodeHandle nh, ros::NodeHandle private_nh);
  // A robot process: reads its private parameters and /swarm, connects its own topics. False
  // (after one ROS_FATAL) on bad input.
  bool Initialize();
  // A robot over `transport`, with its options given and /swarm as read by its host (null: it
  // reads /swarm itself; else it must outlive this call).
  bool Initialize(const RobotNodeOptions& options, std::unique_ptr<RobotTransport> transport,
                  const SwarmConfig* swarm = nullptr);
  // Runs it until ROS shuts down (its transport's loop); false (after one ROS_FATAL) when it
  // cannot tick.
  bool Spin() { return transport_->Spin(config_.tick_period_s); }
  // Sends a last zero velocity (a stopping robot always stands still).
  void Shutdown();
  // Stops every subscription, service and tick, each waiting for its callback in progress, so
  // that nothing of this robot runs any more. Also done by the destructor first: a host removes
  // a robot while its other robots' callbacks run.
  void Disconnect();
  ~RobotNode() override;

  // RobotInbox: what its transport (and a host's shared subscriptions) hand it.
  void TakeRound(const Neighbors::ConstPtr& round, double arrival_s) override;
  void Hand(const core::MissionMessage& message, const core::Sender& from) override;
  void HearRobots(const Robot_Positions& list) override;
  void TimerTick() override;
  void CountDelivered(std::size_t expected, std::size_t delivered) override;

  std::uint64_t ticks() const { return ticks_; }
  double tick_period_s() const { return config_.tick_period_s; }

 private:
  bool lockstep() const { return options_.clock == core::Clock::kLockstep; }
  // A node (un)subscribed its own /flock/position: counts the observers (not the simulator,
  // which keeps only virtual copies and statists of it, nor this process).
  void CountObserver(const std::string& node, int delta);
  // Logs what the session refused, as it says.
  void Say(const core::RobotSession::Taken& taken);
  // Computes and executes one tick on `perception_` (the session decides, the node sends).
  void Tick();
  void PublishStatusIfDue();
  // Its ~state: the session's (StateOf) and the age of its round and its command's listeners.
  Robot_State::Response State() const;
  bool OnState(Robot_State::Request& req, Robot_State::Response& res);
  bool OnDescribe(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  RobotNodeOptions options_;
  SwarmConfig config_;
  std::uint16_t id_ = 0;
  // Declared before everything it connects: its handles' callbacks may run on its queues.
  std::unique_ptr<RobotTransport> transport_;
  std::optional<core::RobotSession> session_;  // its behaviour and state (set by Initialize)
  MissionPublishers mission_pubs_;             // real time (robot_node.cpp says when)
  MissionResender resender_;                   // ... and its statuses re-sent on request
  ros::Publisher position_pub_;
  // Nodes other than the simulator and this process subscribed to its /flock/position (it
  // publishes its own position each tick only while there are some).
  int observers_ = 0;
  std::uint8_t copies_sent_ = 0;           // the virtual copies its last /flock/position announced
  ros::Subscriber position_sub_;           // broadcast comm
  std::unique_ptr<BroadcastHeard> heard_;  // broadcast comm
  std::unique_ptr<RobotStats> stats_;      // diagnostics
  std::map<std::string, WarnThrottle> rejected_;  // by message kind
  WarnThrottle bad_pose_warning_;
  ros::ServiceServer describe_srv_;
  ros::ServiceServer state_srv_;
  std::unique_ptr<NodeDiagnostics> diagnostics_;  // a process of its own
  std::set<std::uint16_t> known_robots_;
  bool listed_ = false;         // it has been in the robot list
  bool said_unlisted_ = false;  // it said once that it is not
  Neighbors::ConstPtr perception_;
  // Real time: the age of its latest round (a stale one stops it; constructed in Initialize).
  core::PoseWatch round_watch_{0.5};
  std::uint64_t ticks_ = 0;
  // Real time: the round perception_ holds was acted on already (TimerTick waits for the next),
  // and how often a tick found it so.
  bool round_acted_ = false;
  std::uint64_t round_waits_ = 0;
  // Real time with the simulator: whether its round shows its last command yet.
  core::CommandEcho echo_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_ROBOT_NODE_H_
