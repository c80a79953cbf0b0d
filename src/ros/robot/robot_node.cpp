#include "swarm_transport/ros/robot/robot_node.h"

#include <geometry_msgs/Twist.h>
#include <ros/callback_queue.h>
#include <std_msgs/String.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

// Neighbors: one message per tick; a robot is never more than one tick behind.
constexpr std::uint32_t kNeighborsQueue = 2;
// Its own loop: rounds kept for its next tick (one per period arrives; more only when it was
// held up, and then the oldest are stale - its diagnostics count them missed).
constexpr std::size_t kRoundsKept = 4;
// Its own ticks: the longest wait between two looks at ros::ok() (ros::shutdown ends a wait at
// once; ros::spin looks every 0.1 s, a wake-up per tick at 10 Hz).
constexpr double kMaxWaitS = 1.0;
// Diagnostics: one line per robot per this many wall seconds on this topic.
constexpr double kStatsPeriodS = 1.0;
constexpr std::uint32_t kStatsQueue = 10;
constexpr std::uint32_t kProgressQueue = 10;
constexpr std::uint32_t kMissionQueue = 256;
// Broadcast comm: every robot publishes once per tick, so the queue must hold a whole swarm's
// tick (as the simulator's); a robot not heard for this many radio rounds is forgotten.
constexpr std::uint32_t kBroadcastQueue = 10000;
constexpr std::uint64_t kForgetRounds = 10;
// Lock-step diagnostics: a broadcast position this close to the radio's truth is current.
constexpr double kCurrentPositionM = 0.01;
// A robot logs one line per kind of rejected message per this many wall seconds (a flood of bad
// messages must not flood the log; issue 11).
constexpr double kRejectLogPeriodS = 10.0;

}  // namespace

std::string RobotNodeOptions::Validate() const {
  std::ostringstream os;
  if (id < 0 || id > 65535) os << "~id must be set to an integer in [0, 65535] but is " << id;
  return os.str();
}

RobotNode::RobotNode(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh) {}

bool RobotNode::Initialize() {
  RobotNodeOptions options;
  std::string error;
  if (!ReadPrivate(private_nh_, "id", &options.id, &error) ||
      !ReadPrivate(private_nh_, "clock", &options.clock, &error) ||
      !ReadPrivate(private_nh_, "comm", &options.comm, &error) ||
      !ReadPrivate(private_nh_, "diagnostics", &options.diagnostics, &error)) {
    ROS_FATAL("robot: invalid parameters: %s", error.c_str());
    return false;
  }
  options.exit_when_removed = true;  // a process of its own
  options.status = true;
  return Initialize(options);
}

bool RobotNode::Initialize(const RobotNodeOptions& options) {
  options_ = options;
  if (OwnLoop()) {
    // Before anything is connected: every callback of its handles runs under its lock.
    locked_queue_ = std::make_unique<LockedCallbackQueue>(ros::getGlobalCallbackQueue(), &mutex_);
    nh_.setCallbackQueue(locked_queue_.get());
    private_nh_.setCallbackQueue(locked_queue_.get());
  }
  std::string error = options_.Validate();
  XmlRpc::XmlRpcValue swarm;
  if (error.empty() && options_.swarm != nullptr) {
    config_ = *options_.swarm;
  } else if (error.empty() && nh_.getParam("/swarm", swarm)) {
    ConfigFromXmlRpc(swarm, &config_, &error);
  }
  if (error.empty()) error = config_.Validate();
  if (!error.empty()) {
    ROS_FATAL("robot: invalid parameters: %s", error.c_str());
    return false;
  }
  id_ = static_cast<std::uint16_t>(options_.id);
  session_.emplace(id_, config_);

  // Who listens to its own /flock/position besides the simulator (which keeps only virtual
  // copies and statists of it): connect and disconnect callbacks run on its own queue.
  position_pub_ = nh_.advertise<Robot_Position>(
      names::kPosition, 10,
      [this](const ros::SingleSubscriberPublisher& s) { CountObserver(s.getSubscriberName(), 1); },
      [this](const ros::SingleSubscriberPublisher& s) {
        CountObserver(s.getSubscriberName(), -1);
      });
  if (options_.direct == nullptr) {
    if (options_.clock == core::Clock::kLockstep) {
      answer_pub_ = nh_.advertise<Tick_Answer>(names::kAnswer, 2);
    } else {
      cmd_pub_ = nh_.advertise<geometry_msgs::Twist>(names::kCmdVel, 2);
    }
    // tcpNoDelay: a tick's perception is one small message; Nagle would add ~40 ms per tick.
    if (OwnLoop()) {
      // Put into its mailbox by roscpp's receiving thread; taken at its next tick (OnTickDue).
      ros::SubscribeOptions ops = ros::SubscribeOptions::create<Neighbors>(
          names::kNeighbors, kNeighborsQueue,
          [this](const Neighbors::ConstPtr& msg) {
            mailbox_.Put(msg, ros::WallTime::now().toSec(), kRoundsKept);
          },
          ros::VoidConstPtr(), &inline_queue_);
      ops.transport_hints = ros::TransportHints().tcpNoDelay();
      neighbors_sub_ = nh_.subscribe(ops);
    } else {
      neighbors_sub_ = nh_.subscribe(names::kNeighbors, kNeighborsQueue, &RobotNode::OnNeighbors,
                                     this, ros::TransportHints().tcpNoDelay());
    }
  }
  // Lock-step: mission messages arrive relayed inside `neighbors`, each at the tick after it
  // was sent, and go out inside the robot's answer: no mission topics, nothing to connect.
  if (options_.clock != core::Clock::kLockstep && !options_.shared_topics) {
    freeze_sub_ = nh_.subscribe(names::kFreeze, 20, &RobotNode::FromTopic<Robot_Freeze>, this);
    continue_sub_ =
        nh_.subscribe(names::kContinue, 20, &RobotNode::FromTopic<Robot_Continue>, this);
    // Up to a dispatcher's whole table of live orders at once (a flood of hand-made ones is
    // the dispatcher's to refuse: the robots take only the orders it admitted).
    mission_sub_ =
        nh_.subscribe(names::kMissionNew, kMissionQueue, &RobotNode::FromTopic<New_Mission>, this);
    update_sub_ =
        nh_.subscribe(names::kObjectUpdate, 20, &RobotNode::FromTopic<Update_Object>, this);
    delete_sub_ =
        nh_.subscribe(names::kObjectDelete, 20, &RobotNode::FromTopic<Delete_Object>, this);
    event_sub_ =
        nh_.subscribe(names::kMissionEvent, 20, &RobotNode::FromTopic<Mission_Event>, this);
    status_sub_ =
        nh_.subscribe(names::kMissionStatus, 50, &RobotNode::FromTopic<Mission_Status>, this);
  }
  if (!options_.shared_topics) {
    robots_sub_ = nh_.subscribe(names::kRobots, 2, &RobotNode::OnRobots, this);
  }
  if (options_.comm == core::Comm::kBroadcast) {
    position_sub_ = nh_.subscribe(names::kPosition, kBroadcastQueue, &RobotNode::OnPosition, this,
                                  ros::TransportHints().tcpNoDelay());
  }
  if (options_.diagnostics) {
    stats_ = std::make_unique<core::TickStats>(config_.tick_period_s,
                                               options_.clock == core::Clock::kRealtime);
    if (!options_.stats_sink) {
      stats_pub_ = nh_.advertise<std_msgs::String>(names::kRobotStats, kStatsQueue);
    }
  }
  if (options_.services) {
    describe_srv_ = private_nh_.advertiseService("describe", &RobotNode::OnDescribe, this);
    state_srv_ = private_nh_.advertiseService("state", &RobotNode::OnState, this);
  }
  if (options_.status) {
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
  ticker_.Stop();
  for (ros::Subscriber* sub :
       {&neighbors_sub_, &freeze_sub_, &continue_sub_, &mission_sub_, &update_sub_, &delete_sub_,
        &event_sub_, &status_sub_, &robots_sub_, &position_sub_}) {
    sub->shutdown();
  }
  describe_srv_.shutdown();
  state_srv_.shutdown();
}

void RobotNode::Shutdown() {
  ticker_.Stop();
  std::lock_guard<std::mutex> lock(mutex_);
  SendCommand(geometry_msgs::Twist());
}

void RobotNode::SendCommand(const geometry_msgs::Twist& command) {
  if (options_.direct != nullptr) {
    options_.direct->SendCommand(id_, command);
  } else if (cmd_pub_) {
    cmd_pub_.publish(command);
  }
}

bool RobotNode::OwnLoop() const {
  return options_.clock == core::Clock::kRealtime && !options_.external_timer &&
         options_.direct == nullptr;
}

bool RobotNode::Spin() {
  if (!OwnLoop()) {
    ros::spin();
    return true;
  }
  std::string error;
  const TickClock::duration period = std::chrono::duration_cast<TickClock::duration>(
      std::chrono::duration<double>(config_.tick_period_s));
  if (!ticker_.Start(
          period, [this] { OnTickDue(); }, &error)) {
    ROS_FATAL("robot %u: cannot tick: %s", id_, error.c_str());
    return false;
  }
  // Its other callbacks (mission topics, the robot list, services, connections) until ROS shuts
  // down (ros::shutdown wakes the wait).
  while (ros::ok()) ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(kMaxWaitS));
  ticker_.Stop();
  return true;
}

void RobotNode::OnTickDue() {
  std::lock_guard<std::mutex> lock(mutex_);
  // Take in what arrived, compute one action and execute it.
  mailbox_.TakeAll(&arrived_);
  for (const RoundMailbox::Arrived& a : arrived_) TakeRound(a.round, a.wall_s);
  arrived_.clear();
  TimerTick();
}

void RobotNode::OnNeighbors(const Neighbors::ConstPtr& msg) {
  TakeRound(msg, ros::WallTime::now().toSec());
}

void RobotNode::CountObserver(const std::string& node, int delta) {
  if (node == names::kSimulatorNode) return;
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
  // Lock-step: the round carries its tick's simulated time, so a robot process needs no /clock
  // (robot.launch remaps it away: one message less per robot and tick); its log lines and
  // anything else on ros::Time see the tick it is in.
  if (options_.clock == core::Clock::kLockstep && ros::Time::isSimTime() &&
      std::isfinite(msg->sim_time) && msg->sim_time >= 0.0 && msg->sim_time < 4.0e9 &&
      ros::Time(msg->sim_time) > ros::Time::now()) {
    ros::Time::setNow(ros::Time(msg->sim_time));
  }
  ApplyTuning(*msg);
  if (options_.clock == core::Clock::kLockstep) ApplyRelayed(*msg);
  if (stats_) RecordRound(*msg, arrival_s);
  if (options_.clock == core::Clock::kLockstep) Tick();
}

void RobotNode::ApplyRelayed(const Neighbors& msg) {
  // The order documented in Neighbors.msg: a mission before its object's moves, those before
  // freeze / continue, signals and phases last. The relay passed on only what counts.
  const core::Sender relay{core::SenderKind::kRelay, 0};
  for (const core::MissionMessage& m : ToMissionMessages(msg)) Hand(m, relay);
}

void RobotNode::ApplyTuning(const Neighbors& msg) {
  const std::uint32_t had = session_->tuning_generation();
  Say(session_->TakeTuning(ToTuning(msg), msg.tick));
  if (session_->tuning_generation() != had) {
    ROS_DEBUG("robot %u: flocking tuning %u from tick %llu", id_, session_->tuning_generation(),
              static_cast<unsigned long long>(msg.tick));
  }
}

void RobotNode::TimerTick() {
  if (perception_) Tick();
}

void RobotNode::OnPosition(const Robot_Position::ConstPtr& msg) {
  // Its own echo and its own virtual copies are not news (the radio drops them too).
  if (msg->robot_id == id_ || !IsFinite(*msg)) return;
  Heard& heard = broadcast_[std::make_pair(msg->robot_id, msg->sub_id)];
  heard.position = msg;
  heard.wall_s = ros::WallTime::now().toSec();
  heard.round = perception_ ? perception_->tick : 0;
}

void RobotNode::RecordRound(const Neighbors& msg, double arrival_s) {
  const double latency = stats_->OnRound(msg.tick, msg.sim_time, arrival_s);
  if (options_.comm != core::Comm::kLocal) return;
  // Local comm: the round carries the in-range robots' updates, delivered within one tick
  // when it arrived within one period of being sampled; a round that never arrived lost as
  // many as this one carries.
  std::size_t in_range = 0;
  for (const Robot_Position& r : msg.robots) {
    if (r.type == Robot_Position::TYPE_PHYSICAL) ++in_range;
  }
  stats_->CountUpdates(in_range * (1 + stats_->last_gap()),
                       latency <= config_.tick_period_s ? in_range : 0);
}

void RobotNode::RecordTick() {
  const ros::WallTime wall_now = ros::WallTime::now();
  const double now = wall_now.toSec();
  stats_->OnTick(now);
  // Broadcast comm: of the robots the radio says are in range this round, those whose own
  // latest position reached this robot in time (real time: it arrived within the last
  // kLateTickFactor periods, as they send one per tick; lock-step: it is their current one).
  if (options_.comm == core::Comm::kBroadcast) {
    std::size_t expected = 0;
    std::size_t delivered = 0;
    for (const Robot_Position& r : perception_->robots) {
      if (r.type != Robot_Position::TYPE_PHYSICAL) continue;
      ++expected;
      const auto it = broadcast_.find(std::make_pair(r.robot_id, std::uint8_t{0}));
      if (it == broadcast_.end()) continue;
      const bool current =
          options_.clock == core::Clock::kRealtime
              ? now - it->second.wall_s <= core::kLateTickFactor * config_.tick_period_s
              : std::hypot(it->second.position->pos_x - r.pos_x,
                           it->second.position->pos_y - r.pos_y) <= kCurrentPositionM;
      delivered += current ? 1 : 0;
    }
    stats_->CountUpdates(expected, delivered);
  }
  // The first tick is reported at once (its wall time is the robot's start-up figure).
  if (!stats_published_.isZero() && (wall_now - stats_published_).toSec() < kStatsPeriodS) {
    return;
  }
  stats_published_ = wall_now;
  std::ostringstream os;
  os.setf(std::ios::fixed);
  os.precision(6);
  os << "id=" << id_ << " clock=" << core::ClockName(options_.clock)
     << " comm=" << core::CommName(options_.comm) << " wall=" << now << " " << stats_->TakeLine();
  if (options_.stats_sink) {
    options_.stats_sink(os.str());
    return;
  }
  std_msgs::String line;
  line.data = os.str();
  stats_pub_.publish(line);
}

void RobotNode::PublishStatusIfDue() {
  if (!diagnostics_) return;
  diagnostics_->PublishIfDue([this](NodeStatus* s) {
    const Robot_State::Response st = State();
    if (!st.listed) {
      s->level = diagnostic_msgs::DiagnosticStatus::WARN;
      s->message = "not in the swarm: idle until spawned";
    } else {
      s->message = "tick " + std::to_string(perception_ ? perception_->tick : 0);
      if (st.frozen) s->message += ", frozen";
      if (st.has_active) {
        s->message +=
            ", mission " + std::to_string(st.active_mission) + (st.leader ? " (leader)" : "");
      }
    }
    s->Add("ticks", st.ticks);
    s->Add("listed", st.listed ? "true" : "false");
    s->Add("frozen", st.frozen ? "true" : "false");
    s->Add("missions", static_cast<std::uint64_t>(st.mission_ids.size()));
    s->Add("heard", static_cast<std::uint64_t>(st.heard));
  });
}

Robot_State::Response RobotNode::State() const {
  const core::RobotBrain& brain = session_->brain();
  const core::MissionPlan& plan = brain.last_plan();
  const core::MoveDecision& move = brain.last_move();
  Robot_State::Response state;
  state.robot_id = id_;
  state.ticks = ticks_;
  state.listed = listed_;
  state.frozen = brain.frozen();
  state.leader = plan.lead || (plan.carry && plan.carry->leader);  // alone or of a transport
  state.has_active = plan.active.has_value();
  state.active_mission = plan.active.value_or(0);
  for (std::uint16_t m : brain.missions().LiveIds()) {
    state.mission_ids.push_back(m);
    state.mission_phases.push_back(static_cast<std::uint8_t>(brain.missions().PhaseOf(m)));
  }
  for (const core::Zone& z : plan.zones) {
    state.zone_ids.push_back(z.id);
    state.zone_safety.push_back(z.inverted);
  }
  state.heard = static_cast<std::uint32_t>(brain.last_heard());
  state.desired_heading_deg = move.desired_heading.degrees();
  state.heading_deg = move.heading.degrees();
  state.distance_m = move.distance_m;
  state.fleeing = move.fleeing;
  state.tuning_generation = session_->tuning_generation();
  state.tuning_tick = session_->tuning_tick();
  const core::FlockingTuning tuning = brain.tuning();
  state.free_will_deg = tuning.free_will_deg;
  state.cohesion = tuning.cohesion;
  state.local_range_m = tuning.local_range_m;
  state.speed_m_per_tick = tuning.speed_m_per_tick;
  return state;
}

bool RobotNode::OnState(Robot_State::Request& /*req*/, Robot_State::Response& res) {
  res = State();
  return true;
}

bool RobotNode::OnDescribe(std_srvs::Trigger::Request& /*req*/, std_srvs::Trigger::Response& res) {
  const Robot_State::Response s = State();
  std::ostringstream os;
  os << "id=" << s.robot_id << " ticks=" << s.ticks << " frozen=" << (s.frozen ? 1 : 0)
     << " role=" << (s.leader ? "leader" : "passive") << " active=";
  if (s.has_active) {
    os << s.active_mission;
  } else {
    os << "none";
  }
  os << " missions=[";
  for (std::size_t i = 0; i < s.mission_ids.size(); ++i) {
    os << s.mission_ids[i] << ":"
       << core::PhaseName(static_cast<core::MissionPhase>(s.mission_phases[i])) << " ";
  }
  os << "] zones=[";
  for (std::size_t i = 0; i < s.zone_ids.size(); ++i) {
    os << s.zone_ids[i] << (s.zone_safety[i] ? ":safety " : ":danger ");
  }
  os << "] heard=" << s.heard << " desired=" << s.desired_heading_deg
     << " heading=" << s.heading_deg << " distance=" << s.distance_m
     << " fleeing=" << (s.fleeing ? 1 : 0) << " free_will=" << s.free_will_deg
     << " cohesion=" << s.cohesion << " range=" << s.local_range_m
     << " speed=" << s.speed_m_per_tick << " tuning=" << s.tuning_generation;
  res.success = true;
  res.message = os.str();
  return true;
}

void RobotNode::OnRobots(const Robot_Positions::ConstPtr& msg) {
  known_robots_.clear();
  for (const Robot_Position& r : msg->robots) {
    if (r.type == Robot_Position::TYPE_PHYSICAL) known_robots_.insert(r.robot_id);
  }
  PublishStatusIfDue();
  if (known_robots_.count(id_) > 0) {
    listed_ = true;
    return;
  }
  if (listed_) {
    listed_ = false;
    ROS_WARN("robot %u: removed from the swarm (%s lists it no more: killed or deleted)%s", id_,
             names::kRobots, options_.exit_when_removed ? "; stopping" : "");
    if (options_.exit_when_removed) ros::requestShutdown();
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
  if (taken.first_leader && options_.clock != core::Clock::kLockstep) AdvertiseMissionOutlets();
  Say(taken);
}

void RobotNode::Say(const core::RobotSession::Taken& taken) {
  switch (taken.say) {
    case core::RobotSession::Taken::Say::kNothing:
      return;
    case core::RobotSession::Taken::Say::kDebug:
      ROS_DEBUG("robot %u: ignored: %s", id_, taken.why.c_str());
      return;
    case core::RobotSession::Taken::Say::kWarn:
      Rejected(taken.kind, taken.why);
      return;
  }
}

void RobotNode::Rejected(const std::string& kind, const std::string& why) {
  WarnThrottle& throttle = rejected_.try_emplace(kind, kRejectLogPeriodS).first->second;
  if (!throttle.Due()) return;
  ROS_WARN("robot %u: rejected %s%s", id_, why.c_str(), throttle.AndMore(kind).c_str());
}

void RobotNode::AdvertiseMissionOutlets() {
  if (status_pub_) return;
  freeze_pub_ = nh_.advertise<Robot_Freeze>(names::kFreeze, 20);
  continue_pub_ = nh_.advertise<Robot_Continue>(names::kContinue, 20);
  update_pub_ = nh_.advertise<Update_Object>(names::kObjectUpdate, 20);
  delete_pub_ = nh_.advertise<Delete_Object>(names::kObjectDelete, 20);
  status_pub_ = nh_.advertise<Mission_Status>(names::kMissionStatus, 50);
  progress_pub_ = nh_.advertise<Mission_Status>(names::kMissionProgress, kProgressQueue);
  LearnExpectedSubscribers();
}

void RobotNode::LearnExpectedSubscribers() {
  outlets_since_ = ros::WallTime::now();
  outlets_ready_ = false;
  if (!QueryTopicNodeCounts(&expected_, true)) expected_ = TopicNodeCounts();
}

bool RobotNode::MissionOutletsReady() {
  if (!status_pub_ || outlets_ready_) return true;
  // A message published before a subscriber connected is lost for it: a first leader holds
  // its phase machine until every node that subscribed when it got the mission is connected
  // (the master told us how many), or 5 s of wall time passed.
  // At least one subscriber (the simulator's relay) even if the master did not answer.
  const auto connected = [this](const ros::Publisher& pub) {
    return pub.getNumSubscribers() >=
           std::max<std::uint32_t>(1, expected_.Subscribers(pub.getTopic()));
  };
  outlets_ready_ = (connected(freeze_pub_) && connected(continue_pub_) && connected(update_pub_) &&
                    connected(delete_pub_) && connected(status_pub_)) ||
                   ros::WallTime::now() - outlets_since_ > ros::WallDuration(5.0);
  return outlets_ready_;
}

void RobotNode::Publish(const Tick_Answer& m) {
  const bool any = !m.object_updates.empty() || !m.freezes.empty() || !m.continues.empty() ||
                   !m.object_deletes.empty() || !m.statuses.empty() || !m.progress.empty();
  if (!any) return;
  if (!status_pub_) {
    ROS_ERROR("robot %u: has mission messages to send but is no first leader", id_);
    return;
  }
  for (const auto& u : m.object_updates) update_pub_.publish(u);
  for (const auto& f : m.freezes) freeze_pub_.publish(f);
  for (const auto& c : m.continues) continue_pub_.publish(c);
  for (const auto& d : m.object_deletes) delete_pub_.publish(d);
  for (const auto& st : m.statuses) status_pub_.publish(st);
  if (progress_pub_) {
    for (const auto& st : m.progress) progress_pub_.publish(st);
  }
}

void RobotNode::Tick() {
  core::Perception in;
  if (options_.comm == core::Comm::kBroadcast) {
    // The thesis's wiring: everything every robot sent (the step filters by range).
    in.self_id = id_;
    in.self = ToPose2(perception_->pose);
    in.others.reserve(broadcast_.size());
    for (auto it = broadcast_.begin(); it != broadcast_.end();) {
      if (it->second.round + kForgetRounds < perception_->tick) {
        it = broadcast_.erase(it);
        continue;
      }
      in.others.push_back(ToNeighbour(*it->second.position));
      ++it;
    }
  } else {
    in = ToPerception(id_, *perception_);
  }
  // Mission peers and relayed robots are positions like any other: the flock group decides
  // whom the swarm runs over, and collisions count everyone.

  const core::Pose2 before = in.self;
  PublishStatusIfDue();
  const bool lockstep = options_.clock == core::Clock::kLockstep;
  // Real time: a robot promoted to first leader (its first leader was lost) connects its
  // mission outlets before it speaks (it takes over the tick after its promotion).
  if (!lockstep && !status_pub_ && session_->brain().missions().IsFirstLeaderOfAny()) {
    AdvertiseMissionOutlets();
  }
  // Lock-step: stamped with the tick's own simulated time (as the batch engine does), not with
  // whatever /clock this process has seen by now.
  const ros::Time stamp = lockstep ? ros::Time(perception_->sim_time) : ros::Time::now();
  core::RobotSession::Step step = session_->Tick(
      std::move(in), perception_->tick, perception_->sim_time, lockstep || MissionOutletsReady());
  const core::Velocity command = step.brain.command;
  const Tick_Answer answer = ToTickAnswer(step.answer, stamp);
  for (const Mission_Status& st : answer.statuses) {
    ROS_INFO("robot %u: mission %u %s", id_, st.mission_id,
             core::PhaseName(static_cast<core::MissionPhase>(st.state)));
  }
  if (lockstep) {
    // One answer: the command and everything said this tick (the simulator relays it and
    // publishes it for observers). Direct links get the same content as the topic.
    if (options_.direct != nullptr) {
      options_.direct->SendAnswer(id_, answer);
    } else {
      answer_pub_.publish(answer);
    }
  } else {
    // Mission messages go out before the command.
    Publish(answer);
    SendCommand(ToTwist(command));
  }
  // Its position for those who listen to robots (broadcast comm, observers in real time). In
  // lock-step with the radio, /flock/positions carries every robot's true pose each tick and the
  // simulator keeps only virtual copies and statists from /flock/position: not published. The
  // same with the simulator in this process (deploy host_sim): it has the robot's true pose, and
  // every publication would be a callback for it to discard - one per robot and tick.
  // In real time the simulator does the same (it discards a robot's own position); the robot
  // sends it while another node listens (observers: rostopic, rosbag, robots of broadcast comm).
  const bool for_observers = !lockstep && options_.direct == nullptr && observers_ > 0;
  if (for_observers || options_.comm == core::Comm::kBroadcast) {
    const core::Pose2 after = core::TurnThenDrive(before, command, config_.tick_period_s);
    // By shared pointer: roscpp hands it to subscribers in this process (the simulator of a
    // robot_host) without serialising it and without waking its poll thread; a message
    // published by reference is serialised, and signals that thread, even for them.
    position_pub_.publish(boost::make_shared<Robot_Position>(ToRobotPosition(id_, after)));
  }
  ++ticks_;
  if (stats_) RecordTick();
}

}  // namespace swarm_transport
