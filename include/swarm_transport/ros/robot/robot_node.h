// The ROS adapter of one robot: perception in, one tick of behaviour, command out.
#ifndef SWARM_TRANSPORT_ROS_ROBOT_NODE_H_
#define SWARM_TRANSPORT_ROS_ROBOT_NODE_H_

#include <ros/ros.h>
#include <std_srvs/Trigger.h>

#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/Delete_Object.h"
#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/Neighbors.h"
#include "swarm_transport/New_Mission.h"
#include "swarm_transport/Robot_Continue.h"
#include "swarm_transport/Robot_Freeze.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/Robot_State.h"
#include "swarm_transport/Tick_Answer.h"
#include "swarm_transport/Update_Object.h"
#include "swarm_transport/core/modes.h"
#include "swarm_transport/core/robot_brain.h"
#include "swarm_transport/core/robot_session.h"
#include "swarm_transport/core/tick_stats.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/diagnostics.h"
#include "swarm_transport/ros/common/direct_link.h"
#include "swarm_transport/ros/common/graph.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/common/wall_throttle.h"
#include "swarm_transport/ros/robot/tick_loop.h"

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
  // ~diagnostics: publish tick timing and delivery figures on /flock/robot_stats once per
  // wall second (benchmarks; off by default).
  bool diagnostics = false;
  // Not a parameter: a host of many robots calls TimerTick() itself instead of every robot
  // ticking on its own (Spin; roscpp's timers re-sort all of a process's timers at every
  // expiry).
  bool external_timer = false;
  // Not a parameter: a host that also runs the simulator links its robots directly. The
  // robot then neither subscribes neighbors nor advertises cmd_vel / answer: its rounds come
  // through OnNeighbors() and its commands and answers go to this outlet (which must outlive
  // the robot).
  RobotOutlet* direct = nullptr;
  // Not a parameter: the robot process stops (ros::requestShutdown) when its id leaves the
  // simulator's robot list (/kill, Delete_Robot), so that a killed robot does not act on and a
  // re-spawned id gets a fresh process. A host of many robots removes them itself instead.
  bool exit_when_removed = false;
  // Not a parameter: the robot does not subscribe the swarm-wide topics (/flock/robots and, in
  // real time, the mission topics); the host that sets this subscribes them once for all its
  // robots and hands every message to each robot's Hear() on the robot's thread. roscpp asks
  // the master five parameters for every subscription callback (its statistics logger), so a
  // subscription per robot and topic was almost all of a host's start-up.
  bool shared_topics = false;
  // Not a parameter: offer ~describe and ~state (a host of many robots may ask for none).
  bool services = true;
  // Not a parameter: the swarm's configuration as read from /swarm by a host of many robots
  // (read once for all of them: a parameter-server round trip per robot was a large part of a
  // 10,000-robot start-up). Null: the robot reads /swarm itself.
  const SwarmConfig* swarm = nullptr;
  // Not a parameter: where its diagnostics lines go instead of its own publication of
  // /flock/robot_stats (a host of many robots sends many robots' lines in one message; must be
  // thread-safe and outlive the robot).
  std::function<void(const std::string&)> stats_sink;
  // Not a parameter: publish its own diagnostic status on /diagnostics (a process of its own;
  // a host of many robots reports once for all of them).
  bool status = false;
  std::string Validate() const;
};

// One robot of the swarm [SPEC 4]. In lock-step every Neighbors message is one tick and is
// answered with exactly one Tick_Answer (its command and its mission messages); in real time it
// ticks every tick_period_s on its own timeline on the latest perception, like the thesis's
// ros::Rate loop (a process of its own: in roscpp's poll thread, see Spin; a host's robots: by
// the host's workers), and publishes cmd_vel and, as a first leader, the mission topics.
class RobotNode {
 public:
  RobotNode(ros::NodeHandle nh, ros::NodeHandle private_nh);
  // Loads and validates parameters, connects topics. False (after one ROS_FATAL) on bad input.
  bool Initialize();
  // The same with the private options given (a host of many robots reads them once).
  bool Initialize(const RobotNodeOptions& options);
  // Real time: one tick on the latest perception (the robot loop's or a host's work).
  void TimerTick();
  // Runs the node until ROS shuts down; false (after one ROS_FATAL) when it cannot tick. A
  // real-time robot of its own process ticks on its own timeline in roscpp's poll thread (the
  // thesis's ros::Rate loop: take in the rounds that arrived, compute and send) while this
  // thread serves its other callbacks under its lock; otherwise ros::spin().
  bool Spin();
  // Sends a last zero velocity (a stopping robot always stands still).
  void Shutdown();
  // Stops every subscription, service and timer (each waits for its callback in progress),
  // so that nothing of this robot runs any more. Also done by the destructor first: a host
  // removes a robot while its other robots' callbacks run.
  void Disconnect();
  ~RobotNode();
  // One radio round (the neighbors subscription's callback; a host with direct links calls it
  // on the robot's callback queue). Lock-step: one tick.
  void OnNeighbors(const Neighbors::ConstPtr& msg);

  // A swarm-wide topic's message, from a host that subscribes for it (shared_topics): what the
  // robot's own subscription would have done with it.
  void Hear(const ros::MessageEvent<Robot_Positions const>& event) {
    OnRobots(event.getConstMessage());
  }
  // A mission topic's message (New_Mission, Update_Object, Delete_Object, Robot_Freeze,
  // Robot_Continue, Mission_Event, Mission_Status).
  template <typename M>
  void Hear(const ros::MessageEvent<M const>& event) {
    FromTopic<M>(event);
  }

  std::uint64_t ticks() const { return ticks_; }
  double tick_period_s() const { return config_.tick_period_s; }

 private:
  // A radio round that arrived at wall time `arrival_s` (OnNeighbors' work).
  void TakeRound(const Neighbors::ConstPtr& msg, double arrival_s);
  // Whether it ticks on its own timeline in the poll thread (Spin) on rounds from its mailbox.
  bool OwnLoop() const;
  // Its tick is due (the poll thread): takes in the rounds that arrived and ticks.
  void OnTickDue();
  // A node (un)subscribed its own /flock/position: counts the observers, the simulator not.
  void CountObserver(const std::string& node, int delta);
  // A mission message with its sender: from a topic (real time) its publisher, relayed inside
  // a lock-step round the relay (which let only what counts through). The session decides;
  // the node says what it refused and, as a new first leader in real time, connects its
  // mission topics.
  void Hand(const core::MissionMessage& message, const core::Sender& from);
  template <typename M>
  void FromTopic(const ros::MessageEvent<M const>& event) {
    Hand(ToMissionMessage(*event.getConstMessage()), SenderOf(event.getPublisherName()));
  }
  // Logs what the session refused, as it says.
  void Say(const core::RobotSession::Taken& taken);
  void OnRobots(const Robot_Positions::ConstPtr& msg);
  // Lock-step: applies the mission messages the simulator relayed with this perception.
  void ApplyRelayed(const Neighbors& msg);
  // A round's flocking tuning (issue 13): a generation it does not have yet is used from this
  // tick on (lock-step: every robot at the same tick; real time: on receipt).
  void ApplyTuning(const Neighbors& msg);
  // Broadcast comm: remembers the latest position of every other robot and copy.
  void OnPosition(const Robot_Position::ConstPtr& msg);
  // Diagnostics: a round's arrival at wall time `arrival_s` (and, local comm, its updates'
  // delivery).
  void RecordRound(const Neighbors& msg, double arrival_s);
  // Diagnostics: this tick's timing (and, broadcast comm, the updates' delivery); publishes
  // the figures once per wall second.
  void RecordTick();
  // ~state: its state, typed (for tools and tests); ~describe: the same in one line for people.
  Robot_State::Response State() const;
  bool OnState(Robot_State::Request& req, Robot_State::Response& res);
  bool OnDescribe(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);
  // Its velocity command, over the direct link or the cmd_vel topic.
  void SendCommand(const geometry_msgs::Twist& command);
  // Computes and executes one tick on `perception_` (the brain decides, the node sends).
  void Tick();
  // Real time: publishes them on the mission topics (/flock/mission/status, .../progress, ...).
  void Publish(const Tick_Answer& messages);
  // Logs a rejected message: one line per kind per kRejectLogPeriodS, with how many of that
  // kind it did not log since.
  void Rejected(const std::string& kind, const std::string& why);
  // Real time: a first leader needs its own publishers; only those robots advertise them, so
  // the swarm does not become all-to-all. True when every robot can hear them.
  bool MissionOutletsReady();
  // Real time: the publishers a first leader needs (when it first becomes one).
  void AdvertiseMissionOutlets();
  // Asks the master how many nodes subscribe to each mission topic (once per new outlet).
  void LearnExpectedSubscribers();

  // Declared before every publisher, subscriber and service of the handles below, so that
  // they outlive them: a real-time robot process runs its handles' callbacks on the spinning
  // thread under mutex_ (locked_queue_), and its rounds' callback where they arrive.
  std::mutex mutex_;
  std::unique_ptr<LockedCallbackQueue> locked_queue_;
  InlineCallbackQueue inline_queue_;
  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  RobotNodeOptions options_;
  SwarmConfig config_;
  std::uint16_t id_ = 0;
  // Its behaviour and state (set by Initialize).
  std::optional<core::RobotSession> session_;
  ros::Publisher cmd_pub_;
  ros::Publisher position_pub_;
  // Nodes other than the simulator subscribed to its /flock/position (real time: it publishes
  // its own position each tick only while there are some).
  int observers_ = 0;
  ros::Subscriber neighbors_sub_;
  ros::Subscriber freeze_sub_;
  ros::Subscriber continue_sub_;
  ros::Subscriber mission_sub_;
  ros::Subscriber update_sub_;
  ros::Subscriber delete_sub_;
  ros::Subscriber event_sub_;
  ros::Subscriber status_sub_;
  ros::Subscriber robots_sub_;
  // Lazily advertised when this robot becomes a first leader (see MissionOutletsReady).
  ros::Publisher freeze_pub_;
  ros::Publisher continue_pub_;
  ros::Publisher update_pub_;
  ros::Publisher delete_pub_;
  ros::Publisher status_pub_;
  // Progress within a phase (not relayed, not counted for the lock-step barrier): advertised
  // when this robot first becomes a first leader.
  ros::Publisher progress_pub_;
  std::map<std::string, WarnThrottle> rejected_;  // by message kind
  WarnThrottle bad_pose_warning_;
  TopicNodeCounts expected_;  // the graph when it became a first leader
  ros::WallTime outlets_since_;
  bool outlets_ready_ = false;
  ros::ServiceServer describe_srv_;
  ros::ServiceServer state_srv_;
  std::unique_ptr<NodeDiagnostics> diagnostics_;  // with options_.status
  void PublishStatusIfDue();
  ros::Publisher answer_pub_;  // lock-step, without a direct link
  // Real time, a process of its own (OwnLoop): its rounds, put here by roscpp's receiving
  // thread (inline_queue_) and taken at its next tick, which ticker_ runs in that thread under
  // mutex_ (its other callbacks: see locked_queue_).
  RoundMailbox mailbox_;
  std::vector<RoundMailbox::Arrived> arrived_;
  PollThreadTicker ticker_;
  std::set<std::uint16_t> known_robots_;
  bool listed_ = false;         // it has been in the robot list
  bool said_unlisted_ = false;  // it said once that it is not
  Neighbors::ConstPtr perception_;
  std::uint64_t ticks_ = 0;
  // Broadcast comm: what each (robot_id, sub_id) last sent, and when (wall s, radio round).
  struct Heard {
    Robot_Position::ConstPtr position;
    double wall_s = 0.0;
    std::uint64_t round = 0;
  };
  ros::Subscriber position_sub_;
  std::map<std::pair<std::uint16_t, std::uint8_t>, Heard> broadcast_;
  // Diagnostics (null when off).
  std::unique_ptr<core::TickStats> stats_;
  ros::Publisher stats_pub_;
  ros::WallTime stats_published_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_ROBOT_NODE_H_
