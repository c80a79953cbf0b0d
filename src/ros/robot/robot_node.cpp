#include "swarm_transport/ros/robot/robot_node.h"

#include <geometry_msgs/Twist.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <variant>

#include "swarm_transport/core/hardware.h"
#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

// Broadcast comm: every robot publishes once per tick, so the queue must hold a whole swarm's
// tick (as the simulator's).
constexpr std::uint32_t kBroadcastQueue = 10000;

}  // namespace

RobotNode::RobotNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh) {}

bool RobotNode::Initialize(const RobotNodeOptions& options,
                           std::unique_ptr<RobotTransport> transport, const SwarmConfig* swarm) {
  options_ = options;
  transport_ = std::move(transport);
  transport_->Prepare(&nh_, &private_nh_);
  std::string error = options_.Validate();
  XmlRpc::XmlRpcValue dict;
  if (error.empty() && swarm != nullptr) {
    config_ = *swarm;
  } else if (error.empty() && nh_.getParam("/swarm", dict)) {
    ConfigFromXmlRpc(dict, &config_, &error);
  }
  if (error.empty()) error = config_.Validate();
  if (!error.empty()) {
    ROS_FATAL("robot: invalid parameters: %s", error.c_str());
    return false;
  }
  id_ = static_cast<std::uint16_t>(options_.id);
  session_.emplace(id_, config_);
  round_watch_ = core::PoseWatch(config_.lost_after_s);
  // A real-time simulation relays its pose from the simulator's world while its process misses
  // ticks; lock-step makes it quiet, and a robot that announces its own position falls silent.
  session_->set_heard_while_hung(!lockstep() && !transport_->AnnouncesPosition() &&
                                 options_.comm != core::Comm::kBroadcast);
  // Who listens to its own /flock/position: connect and disconnect callbacks run on its queue.
  position_pub_ = nh_.advertise<Robot_Position>(
      names::kPosition, 10,
      [this](const ros::SingleSubscriberPublisher& s) { CountObserver(s.getSubscriberName(), 1); },
      [this](const ros::SingleSubscriberPublisher& s) {
        CountObserver(s.getSubscriberName(), -1);
      });
  transport_->Connect(nh_, TransportOptions{id_, options_.clock, options_.diagnostics, &config_},
                      this);
  if (options_.comm == core::Comm::kBroadcast) {
    heard_ = std::make_unique<BroadcastHeard>();
    position_sub_ =
        nh_.subscribe<Robot_Position>(names::kPosition, kBroadcastQueue,
                                      boost::function<void(const Robot_Position::ConstPtr&)>(
                                          [this](const Robot_Position::ConstPtr& msg) {
                                            heard_->Hear(id_, msg, ros::WallTime::now().toSec(),
                                                         perception_ ? perception_->tick : 0);
                                          }),
                                      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  }
  if (options_.diagnostics) {
    stats_ = std::make_unique<RobotStats>(id_, options_.clock, options_.comm, config_.tick_period_s,
                                          options_.hardware);
  }
  // A real-time simulation's robot in a process of its own: its mission publishers and its
  // resender from the start, not when it first leads. Every subscriber (each robot, the
  // simulator, the dispatcher, the recorder) connects once, while the swarm starts, so a first
  // leader's first messages find them connected and its open descriptors stay flat for the rest
  // of its life (docs/reliability.md). A robot host advertises them when one of its robots
  // first leads (one process's publishers serve all of its robots), a robot on hardware when it
  // first leads: a full mesh of connections at start-up would crowd a slow radio link.
  if (!lockstep() && transport_->OwnProcess() && !options_.hardware) {
    mission_pubs_.Advertise(nh_);
    resender_.Start(nh_);
  }
  if (transport_->OffersServices()) {
    describe_srv_ = private_nh_.advertiseService("describe", &RobotNode::OnDescribe, this);
    state_srv_ = private_nh_.advertiseService("state", &RobotNode::OnState, this);
  }
  if (transport_->OwnProcess()) {
    diagnostics_ =
        std::make_unique<NodeDiagnostics>(nh_, "swarm_transport: robot " + std::to_string(id_));
  }
  ROS_INFO("robot %u: up (%s clock, tick %.3f s, range %.3f m, speed %.3f m/tick)", id_,
           core::ClockName(options_.clock), config_.tick_period_s, config_.flocking.local_range_m,
           config_.flocking.speed_m_per_tick);
  if (options_.comm != core::Comm::kLocal || options_.diagnostics) {
    ROS_INFO("robot %u: %s comm, diagnostics %s", id_, core::CommName(options_.comm),
             options_.diagnostics ? "on" : "off");
  }
  return true;
}

RobotNode::~RobotNode() { Disconnect(); }

void RobotNode::Disconnect() {
  if (transport_) transport_->Disconnect();
  position_sub_.shutdown();
  describe_srv_.shutdown();
  state_srv_.shutdown();
}

void RobotNode::Shutdown() {
  transport_->Stop();
  transport_->SendCommand(geometry_msgs::Twist());
}

void RobotNode::CountObserver(const std::string& node, int delta) {
  if (node == names::kSimulatorNode || node == ros::this_node::getName()) return;
  observers_ = std::max(0, observers_ + delta);
}

void RobotNode::TakeRound(const Neighbors::ConstPtr& msg, double arrival_s) {
  if (!std::isfinite(msg->pose.x) || !std::isfinite(msg->pose.y) ||
      !std::isfinite(msg->pose.theta)) {
    if (bad_pose_warning_.Due()) {
      ROS_WARN("robot %u: rejected a perception with a non-finite own pose%s", id_,
               bad_pose_warning_.AndMore("such perceptions").c_str());
    }
    return;
  }
  perception_ = msg;
  round_acted_ = false;
  // Wall time when taken (at most a tick after it arrived): a transport's `arrival_s` may be on
  // another clock (a robot on hardware stamps its rounds with ros::Time, simulated under a bag).
  round_watch_.Took(ros::WallTime::now().toSec());
  // Lock-step: the round carries its tick's simulated time, so a robot process needs no /clock
  // (robot.launch remaps it away: one message less per robot and tick); its log lines and
  // anything else on ros::Time see the tick it is in.
  if (lockstep() && ros::Time::isSimTime() && std::isfinite(msg->sim_time) &&
      msg->sim_time >= 0.0 && msg->sim_time < 4.0e9 &&
      ros::Time(msg->sim_time) > ros::Time::now()) {
    ros::Time::setNow(ros::Time(msg->sim_time));
  }
  // A round's flocking tuning (issue 13): a generation it does not have yet is used from this
  // tick on (lock-step: every robot at the same tick; real time: on receipt).
  const std::uint32_t had = session_->tuning_generation();
  Say(session_->TakeTuning(ToTuning(*msg), msg->tick));
  if (session_->tuning_generation() != had) {
    ROS_DEBUG("robot %u: flocking tuning %u from tick %llu", id_, session_->tuning_generation(),
              static_cast<unsigned long long>(msg->tick));
  }
  if (lockstep()) {
    // The order documented in Neighbors.msg: a mission before its object's moves, those before
    // freeze / continue, signals and phases last. The relay passed on only what counts.
    const core::Sender relay{core::SenderKind::kRelay, 0};
    for (const core::MissionMessage& m : ToMissionMessages(*msg)) Hand(m, relay);
  }
  if (stats_) stats_->OnRound(*msg, arrival_s);
  if (lockstep()) Tick();
}

void RobotNode::CountDelivered(std::size_t expected, std::size_t delivered) {
  if (stats_) stats_->CountDelivered(expected, delivered);
}

void RobotNode::HearRobots(const Robot_Positions& msg) {
  known_robots_.clear();
  for (const Robot_Position& r : msg.robots) {
    if (r.type == Robot_Position::TYPE_PHYSICAL) known_robots_.insert(r.robot_id);
  }
  PublishStatusIfDue();
  if (known_robots_.count(id_) > 0) {
    listed_ = true;
    return;
  }
  const bool exits = transport_->OwnProcess();
  if (listed_) {
    listed_ = false;
    ROS_WARN("robot %u: removed from the swarm (%s lists it no more: killed or deleted)%s", id_,
             names::kRobots, exits ? "; stopping" : "");
    if (exits) ros::requestShutdown();
  } else if (!said_unlisted_) {
    said_unlisted_ = true;
    ROS_WARN(
        "robot %u: not in the swarm (%s has no robot %u): it idles until the simulator "
        "spawns it (rosservice call /spawn, or a New_Robot on %s)",
        id_, names::kRobots, id_, names::kRobotNew);
  }
}

void RobotNode::Hand(const core::MissionMessage& message, const core::Sender& from) {
  const core::RobotSession::Taken taken = session_->Take(message, from, known_robots_);
  // Real time: a new first leader publishes its statuses on topics of its own (lock-step: its
  // answers carry them); published with this tick's messages.
  if (taken.first_leader && !lockstep()) mission_pubs_.Advertise(nh_);
  if (const auto* status = std::get_if<core::PhaseStatus>(&message)) {
    if (taken.why.empty() && (status->phase == core::MissionPhase::kDone ||
                              status->phase == core::MissionPhase::kAborted)) {
      resender_.Ended(status->mission_id);
    }
  }
  Say(taken);
}

void RobotNode::Tick() {
  // Broadcast comm: the thesis's wiring, everything every robot sent (the step filters by
  // range). Mission peers and relayed robots are positions like any other: the flock group
  // decides whom the swarm runs over, and collisions count everyone.
  core::Perception in =
      heard_ ? heard_->Perceive(id_, *perception_) : ToPerception(id_, *perception_);
  // Real time with the simulator: a round made before its last command arrived shows the pose
  // before that command's turn; it plans from where that command takes it (core::CommandEcho).
  const bool echo = !lockstep() && transport_->SimulatorTurnsOnReceipt();
  if (echo) in.self = echo_.PlanFrom(in.self);
  const core::Pose2 before = in.self;
  PublishStatusIfDue();
  // Real time: a robot promoted to first leader (its first leader was lost) connects its
  // mission publishers before it speaks (it takes over the tick after its promotion).
  if (!lockstep() && !mission_pubs_.advertised() &&
      session_->brain().missions().IsFirstLeaderOfAny()) {
    mission_pubs_.Advertise(nh_);
  }
  // Lock-step: stamped with the tick's own simulated time (as the batch engine does), not with
  // whatever /clock this process has seen by now.
  const ros::Time stamp = lockstep() ? ros::Time(perception_->sim_time) : ros::Time::now();
  core::RobotSession::Step step = session_->Tick(
      std::move(in), perception_->tick, perception_->sim_time, lockstep() || mission_pubs_.Ready());
  const Tick_Answer answer = ToTickAnswer(step.answer, stamp);
  const core::Velocity command = step.brain.command;
  if (echo) echo_.Sent(before, command, config_.tick_period_s);
  for (const Mission_Status& st : answer.statuses) {
    ROS_INFO("robot %u: mission %u %s", id_, st.mission_id,
             core::PhaseName(static_cast<core::MissionPhase>(st.state)));
  }
  if (lockstep()) {
    // One answer: the command and everything said this tick (the simulator relays it and
    // publishes it for observers).
    transport_->SendAnswer(answer);
  } else {
    // Mission messages go out before the command.
    if (!mission_pubs_.Publish(answer)) {
      ROS_ERROR("robot %u: has mission messages to send but is no first leader", id_);
    }
    // A first leader re-sends its missions' latest statuses when a restarted dispatcher or
    // recorder asks (docs/reliability.md).
    if (mission_pubs_.advertised()) resender_.Start(nh_);
    for (const Mission_Status& st : answer.statuses) {
      resender_.Remember(st, session_->brain().missions().Find(st.mission_id));
    }
    transport_->SendCommand(ToTwist(command));
  }
  // Its position for those who listen to robots: observers (rostopic, rosbag) in every
  // deployment and clock, robots of broadcast comm and, on hardware, every robot. The simulator is
  // no observer: it has every robot's true pose, keeps only virtual copies and statists from
  // /flock/position, and every publication would be a callback for it to discard - one per robot
  // and tick. A leader that announces virtual copies (SPEC 9.2) carries them on its position:
  // in real time the simulator takes them from there (lock-step: from its answer), so it
  // publishes while it has copies and once more when they end.
  const std::uint8_t copies = step.answer.copies;
  const bool announce = !lockstep() && (copies > 0 || copies_sent_ > 0);
  if (observers_ > 0 || heard_ || transport_->AnnouncesPosition() || announce) {
    const core::Pose2 after = core::TurnThenDrive(before, command, config_.tick_period_s);
    Robot_Position position = ToRobotPosition(id_, after);
    position.copies = copies;
    copies_sent_ = copies;
    // By shared pointer: roscpp hands it to subscribers in this process (the simulator of a
    // robot_host) without serialising it and without waking its poll thread; a message
    // published by reference is serialised, and signals that thread, even for them.
    position_pub_.publish(boost::make_shared<Robot_Position>(position));
  }
  ++ticks_;
  if (stats_) {
    const std::string line = stats_->OnTick(*perception_, heard_.get());
    if (!line.empty()) transport_->SendStats(line);
  }
}

}  // namespace swarm_transport
