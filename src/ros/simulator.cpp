#include "swarm_transport/ros/simulator.h"

#include <rosgraph_msgs/Clock.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <type_traits>

#include "swarm_transport/Pose.h"
#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/ros/conversions.h"
#include "swarm_transport/ros/graph.h"
#include "swarm_transport/ros/names.h"

namespace swarm_transport {
namespace {

constexpr char kClockTopic[] = "/clock";
constexpr int kMaxRobots = 65536;
// Queue sizes. Neighbors: one message per tick, a robot is never more than one tick behind.
// cmd_vel: lock-step sends one per tick; real time may burst. /flock/position: every robot
// publishes every tick and only virtual copies / statists matter, so it must hold a whole
// swarm's tick. /flock/positions: the recorder must see every lock-step tick.
constexpr std::uint32_t kNeighborsQueue = 2;
constexpr std::uint32_t kPoseQueue = 10;
constexpr std::uint32_t kCmdVelQueue = 10;
// Lock-step answers: one per robot and tick; late ones may queue behind the current one.
constexpr std::uint32_t kAnswerQueue = 10;
constexpr std::uint32_t kPositionQueue = 10000;
constexpr std::uint32_t kPositionsQueue = 100;
// Lock-step runs thousands of ticks per second in one process (deploy:=host_sim): a recorder
// or a runner that falls behind for a moment must not lose frames (a sample would move to a
// later tick). Memory is used only while a subscriber lags.
constexpr std::uint32_t kLockstepPositionsQueue = 10000;
constexpr std::uint32_t kMissionQueue = 100;
// Polling period of the lock-step wait (s): also bounds a robot-less tick to ~1 ms.
constexpr double kPollS = 0.001;
// Period of the idle loop after the last lock-step tick and of the start wait (s).
constexpr double kIdleS = 0.01;
// A robot must be connected this long (wall s) before lock-step counts on its answers.
constexpr double kSettleS = 0.2;
// At most one warning of a kind per this many wall seconds (ROS_*_THROTTLE uses ros::Time,
// which stands still at 0 under use_sim_time before /clock runs).
constexpr double kWarnPeriodS = 5.0;
// True (and `last` updated) when `period_s` of wall time passed since the last true.
bool WallThrottle(ros::WallTime* last, double period_s) {
  const ros::WallTime now = ros::WallTime::now();
  if (!last->isZero() && (now - *last).toSec() < period_s) return false;
  *last = now;
  return true;
}

// A teleport service's answer: OK, or ERROR with the reason (also logged).
template <typename Response>
bool Reply(bool ok, const char* service, std::uint16_t id, const std::string& error,
           Response* res) {
  if (!ok) ROS_WARN("simulator: %s of robot %u rejected: %s", service, id, error.c_str());
  res->code = ok ? Response::OK : Response::ERROR;
  res->message = ok ? "ok" : error;
  return true;
}

}  // namespace

std::string SimulatorParams::Validate() const {
  std::ostringstream os;
  const std::string swarm_error = swarm.Validate();
  if (!swarm_error.empty()) {
    os << "/swarm: " << swarm_error;
  } else if (!std::isfinite(radio_loss) || radio_loss < 0.0 || radio_loss > 1.0) {
    os << "/swarm/radio_loss must be a probability in [0, 1] but is " << radio_loss;
  } else if (placement == core::Placement::kFile && placement_file.empty()) {
    os << "~placement_file must name a file when ~placement is file";
  } else if (robots > kMaxRobots || robots < (placement == core::Placement::kFile ? -1 : 0)) {
    os << "~robots must be in [0, " << kMaxRobots << "] but is " << robots;
  } else if (!std::isfinite(lockstep_timeout_s) || !(lockstep_timeout_s > 0.0)) {
    os << "~lockstep_timeout_s must be > 0 but is " << lockstep_timeout_s;
  } else if (lockstep_max_ticks < 0) {
    os << "~lockstep_max_ticks must be >= 0 (0: unbounded) but is " << lockstep_max_ticks;
  } else if (lockstep_observers < 0) {
    os << "~lockstep_observers must be >= 0 but is " << lockstep_observers;
  } else if (!std::isfinite(lockstep_start_timeout_s) || lockstep_start_timeout_s < 0.0) {
    os << "~lockstep_start_timeout_s must be >= 0 but is " << lockstep_start_timeout_s;
  } else if (!std::isfinite(real_time_factor) || real_time_factor < 0.0) {
    os << "~real_time_factor must be a finite number >= 0 (0: as fast as possible) but is "
       << real_time_factor;
  } else if (!std::isfinite(integration_step_s) || !(integration_step_s > 0.0) ||
             integration_step_s > swarm.tick_period_s) {
    os << "~integration_step_s must be in (0, tick_period_s = " << swarm.tick_period_s
       << "] but is " << integration_step_s;
  } else if (!std::isfinite(markers_rate_hz) || markers_rate_hz < 0.0) {
    os << "~markers_rate_hz must be >= 0 (0: off) but is " << markers_rate_hz;
  } else if (!std::isfinite(radio_range_m) || !(radio_range_m > 0.0)) {
    os << "~radio_range_m must be > 0 but is " << radio_range_m;
  }
  return os.str();
}

volatile std::sig_atomic_t Simulator::stop_requested_ = 0;

Simulator::Simulator(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh) {}

void Simulator::RequestStop() { stop_requested_ = 1; }

bool Simulator::Running() { return stop_requested_ == 0 && ros::ok(); }

bool Simulator::LoadParams(std::string* error) {
  XmlRpc::XmlRpcValue swarm;
  if (nh_.getParam("/swarm", swarm) && !ConfigFromXmlRpc(swarm, &params_.swarm, error)) {
    *error = "/swarm: " + *error;
    return false;
  }
  if (nh_.hasParam("/swarm/radio_loss") && !nh_.getParam("/swarm/radio_loss", params_.radio_loss)) {
    *error = "/swarm/radio_loss must be a number";
    return false;
  }
  params_.radio_range_m = params_.swarm.flocking.local_range_m;
  // Directly linked robots (a robot_host that runs the simulator) go without pose topics
  // unless asked for.
  params_.pose_topics = direct_ == nullptr;
  const ros::NodeHandle& p = private_nh_;
  if (!ReadPrivate(p, "placement", &params_.placement, error)) return false;
  // With a placement file, robots defaults to every line of it.
  if (params_.placement == core::Placement::kFile) params_.robots = -1;
  if (!ReadPrivate(p, "robots", &params_.robots, error) ||
      !ReadPrivate(p, "placement_file", &params_.placement_file, error) ||
      !ReadPrivate(p, "clock", &params_.clock, error) ||
      !ReadPrivate(p, "lockstep_timeout_s", &params_.lockstep_timeout_s, error) ||
      !ReadPrivate(p, "lockstep_max_ticks", &params_.lockstep_max_ticks, error) ||
      !ReadPrivate(p, "lockstep_start_timeout_s", &params_.lockstep_start_timeout_s, error) ||
      !ReadPrivate(p, "real_time_factor", &params_.real_time_factor, error) ||
      !ReadPrivate(p, "lockstep_observers", &params_.lockstep_observers, error) ||
      !ReadPrivate(p, "lockstep_dispatcher", &params_.lockstep_dispatcher, error) ||
      !ReadPrivate(p, "integration_step_s", &params_.integration_step_s, error) ||
      !ReadPrivate(p, "markers_rate_hz", &params_.markers_rate_hz, error) ||
      !ReadPrivate(p, "tf", &params_.tf, error) ||
      !ReadPrivate(p, "range_circles", &params_.range_circles, error) ||
      !ReadPrivate(p, "radio_range_m", &params_.radio_range_m, error) ||
      !ReadPrivate(p, "pose_topics", &params_.pose_topics, error)) {
    return false;
  }
  *error = params_.Validate();
  if (!error->empty()) return false;

  sim::WorldParams world;
  world.world_size_m = params_.swarm.flocking.world_size_m;
  world.robot_radius_m = params_.swarm.flocking.robot_radius_m;
  world.integration_step_s = params_.integration_step_s;
  // A command is one tick's move: it is held exactly one tick (turtlesim holds 1 s).
  world.command_duration_s = params_.swarm.tick_period_s;
  *error = world.Validate();
  if (!error->empty()) return false;
  world_ = std::make_unique<sim::World2D>(world);
  lockstep_ = params_.clock == core::Clock::kLockstep;
  return true;
}

bool Simulator::PlaceInitialRobots(std::string* error) {
  return sim::PlaceInitialRobots(params_.placement, params_.swarm.seed, params_.placement_file,
                                 &params_.robots, world_.get(), error);
}

bool Simulator::Initialize() {
  thread_ = std::this_thread::get_id();
  std::string error;
  if (!LoadParams(&error) || !PlaceInitialRobots(&error)) {
    ROS_FATAL("simulator: invalid parameters: %s", error.c_str());
    return false;
  }
  radio_rng_ = std::make_unique<core::Rng>(params_.swarm.seed, sim::kRadioLossStream);
  sim::RadioParams radio;
  radio.range_m = params_.radio_range_m;
  radio.hops = params_.swarm.flocking.neighbourhood == core::Neighbourhood::kChain
                   ? params_.swarm.chain_hops
                   : 1;
  radio.loss = params_.radio_loss;
  radio_ = std::make_unique<sim::Radio>(radio, radio_rng_.get());

  // Latched: a late subscriber (a test after the last lock-step tick) still gets the state.
  positions_pub_ = nh_.advertise<Robot_Positions>(
      names::kPositions, lockstep_ ? kLockstepPositionsQueue : kPositionsQueue, true);
  robots_pub_ = nh_.advertise<Robot_Positions>(names::kRobots, 1, true);
  if (lockstep_) clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>(kClockTopic, 10);
  sim::VisualsParams visuals;
  visuals.rate_hz = params_.markers_rate_hz;
  visuals.tf = params_.tf;
  visuals.range_circles = params_.range_circles;
  visuals.local_range_m = params_.swarm.flocking.local_range_m;
  visuals.danger_zones = params_.swarm.danger_zones;
  visuals_ = std::make_unique<sim::Visuals>(nh_, std::move(visuals));
  spawn_srv_ = nh_.advertiseService(names::kSpawn, &Simulator::OnSpawn, this);
  kill_srv_ = nh_.advertiseService(names::kKill, &Simulator::OnKill, this);
  reset_srv_ = nh_.advertiseService(names::kReset, &Simulator::OnReset, this);
  // /flock/position also carries every robot's own position each tick; we only keep virtual
  // copies and statists, but the queue must hold a whole tick of the swarm.
  position_sub_ = nh_.subscribe(names::kPosition, kPositionQueue, &Simulator::OnPosition, this,
                                ros::TransportHints().tcpNoDelay());
  robot_delete_sub_ =
      nh_.subscribe(names::kRobotDelete, kMissionQueue, &Simulator::OnRobotDelete, this);
  if (!lockstep_) {
    // Lock-step takes orders in through the relay, at the tick the robots take them.
    mission_new_sub_ =
        nh_.subscribe(names::kMissionNew, kMissionQueue, &Simulator::OnMissionNew, this);
  }
  object_update_sub_ =
      nh_.subscribe(names::kObjectUpdate, kMissionQueue, &Simulator::OnObjectUpdate, this);
  object_delete_sub_ =
      nh_.subscribe(names::kObjectDelete, kMissionQueue, &Simulator::OnObjectDelete, this);
  if (lockstep_) {
    // The lock-step barrier for mission messages: what arrives during tick k is relayed in
    // every Neighbors of tick k + 1 (robots in lock-step do not subscribe to these topics).
    // The relay orders messages by their publishing node (and skips what this node publishes
    // itself), so the callbacks must get the connection header: a lambda given to subscribe<M>() would be wrapped as a
    // `const M::ConstPtr&` callback, whose MessageEvent names every sender "unknown_publisher"
    // (the dispatcher's statuses then counted as a robot's, and a tick could close early).
    auto relay = [this](const char* topic, auto* list) {
      using M = typename std::remove_pointer_t<decltype(list)>::value_type::second_type;
      ros::SubscribeOptions ops;
      ops.initByFullCallbackType<const ros::MessageEvent<const M>&>(
          topic, kMissionQueue, [this, list](const ros::MessageEvent<const M>& event) {
            Relay(event, list);
          });
      relay_subs_.push_back(nh_.subscribe(ops));
    };
    relay(names::kMissionNew, &pending_missions_);
    relay(names::kObjectUpdate, &relay_updates_);
    relay(names::kObjectDelete, &relay_deletes_);
    relay(names::kFreeze, &relay_freezes_);
    relay(names::kContinue, &relay_continues_);
    relay(names::kMissionEvent, &relay_events_);
    relay(names::kMissionStatus, &relay_statuses_);
    // What the robots say in their answers, for observers (robots in lock-step publish no
    // mission topics).
    status_pub_ = nh_.advertise<Mission_Status>(names::kMissionStatus, kMissionQueue);
    progress_pub_ = nh_.advertise<Mission_Status>(names::kMissionProgress, kMissionQueue);
    update_pub_ = nh_.advertise<Update_Object>(names::kObjectUpdate, kMissionQueue);
    delete_pub_ = nh_.advertise<Delete_Object>(names::kObjectDelete, kMissionQueue);
    freeze_pub_ = nh_.advertise<Robot_Freeze>(names::kFreeze, kMissionQueue);
    continue_pub_ = nh_.advertise<Robot_Continue>(names::kContinue, kMissionQueue);
    if (params_.lockstep_dispatcher) {
      // Its file missions enter at stamped ticks; tick 1 on waits for its schedule.
      barrier_.ExpectSchedule();
      schedule_sub_ = nh_.subscribe(names::kMissionSchedule, kMissionQueue,
                                    &Simulator::OnSchedule, this);
      ROS_INFO("lockstep: a dispatcher sends LOADED %s, UNLOADED %s; ticks wait for them",
               params_.swarm.loaded_delay_s >= 0.0 ? "on its own" : "never (waits for you)",
               params_.swarm.unloaded_delay_s >= 0.0 ? "on its own" : "never (waits for you)");
    }
  }
  for (const auto& entry : world_->robots()) AddRobotIo(entry.first);
  PublishRobotList();

  bool use_sim_time = false;
  nh_.getParam("/use_sim_time", use_sim_time);
  if (!lockstep_ && use_sim_time) {
    ROS_WARN("simulator: realtime clock but /use_sim_time is true: nobody publishes /clock");
  }
  ROS_INFO(
      "simulator: %zu robots (%s placement), %s clock, tick %.3f s, step %.3f s, "
      "arena %.3f m, radius %.3f m, radio range %.3f m, loss %.2f, seed %llu",
      world_->size(), core::PlacementName(params_.placement), core::ClockName(params_.clock), params_.swarm.tick_period_s,
      params_.integration_step_s, params_.swarm.flocking.world_size_m,
      params_.swarm.flocking.robot_radius_m, params_.radio_range_m, params_.radio_loss,
      static_cast<unsigned long long>(params_.swarm.seed));
  return true;
}

void Simulator::AddRobotIo(std::uint16_t id) {
  ros::NodeHandle robot_nh(nh_, names::RobotNamespace(id));
  RobotIo io;
  io.generation = ++next_generation_;
  const std::uint64_t generation = io.generation;
  // Status callbacks run on the global queue, i.e. from our own loop like everything else.
  auto counter = [this, id, generation](int RobotIo::*field, int delta) {
    return [this, id, generation, field, delta](const ros::SingleSubscriberPublisher&) {
      CountSubscriber(id, generation, field, delta);
    };
  };
  if (params_.pose_topics) {
    io.pose =
        robot_nh.advertise<Pose>(names::kPose, kPoseQueue, counter(&RobotIo::pose_subscribers, 1),
                                 counter(&RobotIo::pose_subscribers, -1));
  }
  // A robot of this process linked directly: its round, command and answer bypass roscpp.
  io.direct = direct_ != nullptr && direct_->Hosts(id);
  if (!io.direct) {
    io.neighbors = robot_nh.advertise<Neighbors>(names::kNeighbors, kNeighborsQueue,
                                                 counter(&RobotIo::neighbors_subscribers, 1),
                                                 counter(&RobotIo::neighbors_subscribers, -1));
    ros::SubscribeOptions ops = ros::SubscribeOptions::create<geometry_msgs::Twist>(
        names::kCmdVel, kCmdVelQueue,
        [this, id](const geometry_msgs::Twist::ConstPtr& msg) { OnCmdVel(id, *msg); },
        ros::VoidConstPtr(), &cmd_queue_);
    // A tick's command is one small message: Nagle's algorithm would delay it by ~40 ms.
    ops.transport_hints = ros::TransportHints().tcpNoDelay();
    io.cmd_vel = robot_nh.subscribe(ops);
  }
  if (lockstep_ && !io.direct) {
    ros::SubscribeOptions answer_ops = ros::SubscribeOptions::create<Tick_Answer>(
        names::kAnswer, kAnswerQueue,
        [this, id](const Tick_Answer::ConstPtr& msg) { OnAnswer(id, *msg); }, ros::VoidConstPtr(),
        &cmd_queue_);
    answer_ops.transport_hints = ros::TransportHints().tcpNoDelay();
    io.answer = robot_nh.subscribe(answer_ops);
  }
  io.teleport_absolute =
      robot_nh.advertiseService<TeleportAbsolute::Request, TeleportAbsolute::Response>(
          names::kTeleportAbsolute,
          [this, id](TeleportAbsolute::Request& req, TeleportAbsolute::Response& res) {
            return OnTeleportAbsolute(id, req, res);
          });
  io.teleport_relative =
      robot_nh.advertiseService<TeleportRelative::Request, TeleportRelative::Response>(
          names::kTeleportRelative,
          [this, id](TeleportRelative::Request& req, TeleportRelative::Response& res) {
            return OnTeleportRelative(id, req, res);
          });
  io_[id] = io;
  barrier_.Add(id);
}

void Simulator::CountSubscriber(std::uint16_t id, std::uint64_t generation, int RobotIo::*field,
                                int delta) {
  auto it = io_.find(id);
  if (it == io_.end() || it->second.generation != generation) return;
  it->second.*field = std::max(0, it->second.*field + delta);
}

bool Simulator::Ready(RobotIo* io) {
  // Nothing to connect: a direct robot hears its first round and answers it for sure.
  if (io->direct) return true;
  // Only checked until the robot is live: getNumPublishers() scans every subscription.
  const bool connected = io->neighbors_subscribers > 0 && io->answer &&
                         io->answer.getNumPublishers() > 0;
  const ros::WallTime now = ros::WallTime::now();
  if (!connected) {
    io->connected_since = ros::WallTime();
  } else if (io->connected_since.isZero()) {
    io->connected_since = now;
  }
  // A publisher link counts before its handshake is done: a command sent in that window
  // would be lost, so a robot must stay connected a moment before it is asked to answer.
  return connected && (now - io->connected_since).toSec() >= kSettleS;
}

void Simulator::RemoveRobot(std::uint16_t id) {
  world_->Kill(id, nullptr);
  auto it = io_.find(id);
  if (it != io_.end()) {
    RobotIo& io = it->second;
    io.neighbors.shutdown();
    io.pose.shutdown();
    io.cmd_vel.shutdown();
    io.answer.shutdown();
    io.teleport_absolute.shutdown();
    io.teleport_relative.shutdown();
    io_.erase(it);
  }
  barrier_.Remove(id);
  // Its virtual copies die with it.
  for (auto r = relayed_.begin(); r != relayed_.end();) {
    if (r->first.first == id && r->second.type == Robot_Position::TYPE_VIRTUAL) {
      r = relayed_.erase(r);
    } else {
      ++r;
    }
  }
}

void Simulator::Run() {
  start_wall_ = ros::WallTime::now();
  visuals_->Start(start_wall_);
  if (lockstep_) {
    RunLockstep();
  } else {
    RunRealtime();
  }
}

void Simulator::Shutdown() {
  for (auto& entry : io_) {
    entry.second.neighbors.shutdown();
    entry.second.pose.shutdown();
    entry.second.cmd_vel.shutdown();
    entry.second.teleport_absolute.shutdown();
    entry.second.teleport_relative.shutdown();
  }
  io_.clear();
  position_sub_.shutdown();
  robot_delete_sub_.shutdown();
  mission_new_sub_.shutdown();
  schedule_sub_.shutdown();
  object_update_sub_.shutdown();
  object_delete_sub_.shutdown();
  spawn_srv_.shutdown();
  kill_srv_.shutdown();
  reset_srv_.shutdown();
  positions_pub_.shutdown();
  clock_pub_.shutdown();
  if (visuals_) visuals_->Shutdown();
}

void Simulator::SpinOnce(double wait_s) {
  SpinRobots();
  cmd_queue_.callAvailable(ros::WallDuration(wait_s));
  ros::spinOnce();
}

void Simulator::SpinRobots() {
  if (direct_ != nullptr && lockstep_) direct_->SpinRobots();
}

void Simulator::RunRealtime() {
  ros::WallRate rate(1.0 / params_.integration_step_s);
  const ros::WallDuration tick(params_.swarm.tick_period_s);
  ros::WallTime next_radio = start_wall_;
  while (Running()) {
    SpinOnce();
    const ros::WallTime now = ros::WallTime::now();
    if (now >= next_radio) {
      PublishRadio();
      ++tick_;
      next_radio += tick;
      if (next_radio < now) next_radio = now + tick;  // fell behind: skip, do not burst
    }
    world_->Step(params_.integration_step_s);
    PublishPoses();
    PublishVisualsIfDue();
    rate.sleep();
  }
  ROS_INFO("simulator: realtime finished after %llu radio rounds",
           static_cast<unsigned long long>(tick_));
}

bool Simulator::RelaysConnected() const {
  TopicNodeCounts graph;
  if (!QueryTopicNodeCounts(&graph)) return false;
  for (const ros::Subscriber& sub : relay_subs_) {
    if (!graph.AllConnected(sub)) return false;
  }
  // Every subscriber of the (latched) robot list has it: a robot checks a mission's robots
  // against it, and one without it would accept an order naming a robot that does not exist.
  return graph.AllConnected(robots_pub_);
}

void Simulator::WaitForRobots() {
  const ros::WallTime deadline =
      ros::WallTime::now() + ros::WallDuration(params_.lockstep_start_timeout_s);
  std::size_t connected = 0;
  ros::WallTime ready_since;
  while (Running()) {
    connected = 0;
    for (auto& entry : io_) {
      if (Ready(&entry.second)) ++connected;
    }
    const bool observed = params_.lockstep_observers == 0 ||
                          positions_pub_.getNumSubscribers() >=
                              static_cast<std::uint32_t>(params_.lockstep_observers);
    const ros::WallTime now = ros::WallTime::now();
    // Asks the master only once the cheap conditions hold.
    const bool ready = connected == io_.size() && observed && RelaysConnected();
    if (ready) {
      // A link counts before its handshake is done (see Ready), and what was published before
      // the last observer subscribed (a latched mission, one sent just before an experiment's
      // runner subscribes) may still be on its way: everything must stay connected a moment,
      // taking it in, so that it is relayed at tick 0 whatever the scheduling.
      if (ready_since.isZero()) ready_since = now;
      SpinOnce();
      if ((now - ready_since).toSec() >= kSettleS) break;
      ros::WallDuration(kIdleS).sleep();
      continue;
    }
    ready_since = ros::WallTime();
    if (ros::WallTime::now() >= deadline) {
      ROS_WARN(
          "lockstep: only %zu of %zu robots connected (mission relays %s) after %.1f s; "
          "starting anyway (the others join when they connect)",
          connected, io_.size(), RelaysConnected() ? "connected" : "not all connected",
          params_.lockstep_start_timeout_s);
      break;
    }
    SpinOnce();
    PublishVisualsIfDue();
    ros::WallDuration(kIdleS).sleep();
  }
  ROS_INFO("lockstep: %zu robots connected", connected);
}

void Simulator::UpdateLiveness() {
  for (auto& entry : io_) {
    const std::uint16_t id = entry.first;
    RobotIo& io = entry.second;
    const bool live = barrier_.Live(id);
    if (io.silent && !io.direct && io.neighbors_subscribers == 0) {
      io.silent = false;  // gone: a process that connects under its id is a fresh start
      io.connected_since = ros::WallTime();
    }
    if (!live && !io.silent && Ready(&io)) {
      barrier_.MakeLive(id);
      if (tick_ > 0) {
        ROS_INFO("lockstep: robot %u connected at tick %llu", id,
                 static_cast<unsigned long long>(tick_));
      }
    } else if (live && !io.direct && io.neighbors_subscribers == 0) {
      barrier_.MakeNotLive(id);
      io.connected_since = ros::WallTime();
      ROS_WARN("lockstep: robot %u disconnected at tick %llu", id,
               static_cast<unsigned long long>(tick_));
    }
  }
}

void Simulator::WaitForAnswers() {
  const ros::WallTime deadline =
      ros::WallTime::now() + ros::WallDuration(params_.lockstep_timeout_s);
  bool complete = false;
  do {
    // Directly linked robots tick here; their answers are in when this returns.
    SpinRobots();
    ros::spinOnce();
    complete = barrier_.AllAnswered();
    // Block for answers only while some are missing (with direct robots only: none are).
    cmd_queue_.callAvailable(ros::WallDuration(complete ? 0.0 : kPollS));
    complete = barrier_.AllAnswered();
    PublishVisualsIfDue();
  } while (!complete && Running() && ros::WallTime::now() < deadline);
  // Whatever robots sent besides their answers (virtual copies) is in before the next round.
  ros::spinOnce();
  TakeAnswers();
  if (barrier_.AllAnswered() || !Running()) return;
  const std::vector<std::uint16_t> late = barrier_.Late();
  const std::size_t live = barrier_.LiveCount();
  // Out of the barrier until they answer again: a hung or dead robot must not cost the
  // timeout every tick. They stand; they still are in the world and heard by the others.
  for (std::uint16_t id : late) {
    barrier_.MakeNotLive(id);
    auto it = io_.find(id);
    if (it != io_.end()) it->second.silent = true;
  }
  if (WallThrottle(&last_late_warning_wall_, kWarnPeriodS)) {
    ROS_WARN(
        "lockstep tick %llu: %zu of %zu robots did not answer within %.2f s (first: robot "
        "%d); they stand and are not waited for until they answer again",
        static_cast<unsigned long long>(tick_), late.size(), live, params_.lockstep_timeout_s,
        late.empty() ? -1 : static_cast<int>(late.front()));
  }
}

void Simulator::ApplyAnswers() {
  for (const auto& entry : io_) {
    if (!barrier_.Live(entry.first)) continue;
    world_->SetCommand(entry.first, barrier_.CommandOf(entry.first), nullptr);
  }
}

void Simulator::RunLockstep() {
  WaitForRobots();
  const ros::WallTime started = ros::WallTime::now();
  const std::uint64_t max_ticks = static_cast<std::uint64_t>(params_.lockstep_max_ticks);
  while (Running() && (max_ticks == 0 || tick_ < max_ticks)) {
    UpdateLiveness();
    // A phase status relayed now makes its dispatcher event due in this tick's relay.
    WaitForDispatcher();
    PublishClock();
    PublishRadio();
    PublishPoses();
    WaitForAnswers();
    // All answers of this tick apply together: the result does not depend on arrival order.
    ApplyAnswers();
    world_->Step(params_.swarm.tick_period_s);
    ++tick_;
    if (params_.real_time_factor > 0.0) {
      // Paced: tick k ends no earlier than k * tick_period / factor wall seconds after the
      // start (a late tick is not made up for by rushing the next ones).
      const ros::WallTime due =
          started + ros::WallDuration(static_cast<double>(tick_) * params_.swarm.tick_period_s /
                                      params_.real_time_factor);
      while (Running() && ros::WallTime::now() < due) {
        SpinOnce(std::min(kIdleS, std::max(0.0, (due - ros::WallTime::now()).toSec())));
        PublishVisualsIfDue();
      }
    }
    if (tick_ % 100 == 0) {
      ROS_DEBUG("lockstep: tick %llu, %.1f ticks/s", static_cast<unsigned long long>(tick_),
                tick_ / std::max(1e-9, (ros::WallTime::now() - started).toSec()));
    }
  }
  const double wall_s = std::max(1e-9, (ros::WallTime::now() - started).toSec());
  ROS_INFO("lockstep finished after %llu ticks (%.1f ticks/s)",
           static_cast<unsigned long long>(tick_), tick_ / wall_s);
  if (!Running()) return;
  // The final state at the final time, for the recorder and tests; then the world stands.
  finished_ = true;
  PublishClock();
  barrier_.EndAll();  // no Neighbors: nobody is asked to answer
  PublishRadio();
  PublishPoses();
  Idle();
}

void Simulator::Idle() {
  while (Running()) {
    SpinOnce(kIdleS);  // directly linked robots' ~describe services stay up
    PublishVisualsIfDue();
  }
}

double Simulator::SimTime() const {
  if (lockstep_) return static_cast<double>(tick_) * params_.swarm.tick_period_s;
  return (ros::WallTime::now() - start_wall_).toSec();
}

ros::Time Simulator::Stamp() const { return lockstep_ ? ros::Time(SimTime()) : ros::Time::now(); }

void Simulator::PublishClock() {
  // By shared pointer: this process's own /clock subscription (roscpp's, under sim time) gets it
  // without serialisation (see RobotNode::Tick).
  auto msg = boost::make_shared<rosgraph_msgs::Clock>();
  msg->clock = ros::Time(SimTime());
  clock_pub_.publish(msg);
}

void Simulator::PublishRadio() {
  if (lockstep_) ReleaseMissions();
  const double sim_time = SimTime();
  const auto& robots = world_->robots();
  std::vector<Robot_Position> truth;
  truth.reserve(robots.size());
  for (const auto& entry : robots) truth.push_back(ToRobotPosition(entry.first, entry.second.pose));
  std::vector<sim::RadioExtra> extras;
  extras.reserve(relayed_.size());
  for (const auto& entry : relayed_) {
    sim::RadioExtra e;
    e.virtual_copy = entry.second.type == Robot_Position::TYPE_VIRTUAL;
    e.owner = entry.second.robot_id;
    e.position = {entry.second.pos_x, entry.second.pos_y};
    extras.push_back(e);
  }
  // Robots that do not answer their ticks (dead, hung, not connected yet) are silent on the
  // radio: their peers lose them (issue 11). Directly linked robots always answer.
  std::set<std::uint16_t> quiet;
  for (const auto& entry : io_) {
    if (entry.second.direct) continue;
    const bool answering = lockstep_ ? barrier_.Live(entry.first)
                                     : entry.second.neighbors_subscribers > 0;
    if (!answering) quiet.insert(entry.first);
  }
  radio_->Begin(*world_, std::move(extras), missions_, quiet);
  // Virtual copies are relayed at their owner's true pose, the others where announced.
  std::vector<Robot_Position> relayed;
  relayed.reserve(relayed_.size());
  std::size_t k = 0;
  for (const auto& entry : relayed_) {
    Robot_Position p = entry.second;
    const long owner = radio_->extra_owner()[k++];
    if (owner >= 0) {
      p.pos_x = truth[static_cast<std::size_t>(owner)].pos_x;
      p.pos_y = truth[static_cast<std::size_t>(owner)].pos_y;
      p.angle = truth[static_cast<std::size_t>(owner)].angle;
    }
    relayed.push_back(p);
  }

  sim::RadioRound round;
  barrier_.StartTick(tick_);
  std::size_t i = 0;
  for (auto robot = robots.begin(); robot != robots.end(); ++robot, ++i) {
    auto io = io_.find(robot->first);
    if (io == io_.end()) continue;
    const bool deliver =
        lockstep_ ? barrier_.Live(robot->first)
                  : io->second.direct || io->second.neighbors_subscribers > 0;
    if (!deliver) continue;
    radio_->Hear(i, &round);
    Neighbors msg = RadioRoundMessage(tick_, sim_time, robot->second, round, truth, relayed);
    if (lockstep_) FillRelay(&msg);
    if (io->second.direct) {
      direct_->Deliver(robot->first, boost::make_shared<const Neighbors>(std::move(msg)));
    } else {
      io->second.neighbors.publish(msg);
    }
    if (lockstep_) barrier_.Ask(robot->first);
  }

  ClearRelay();
  Robot_Positions all;
  all.tick = tick_;
  all.sim_time = sim_time;
  all.robots = std::move(truth);
  positions_pub_.publish(all);
}

template <typename M>
void Simulator::Relay(const ros::MessageEvent<const M>& event, RelayList<M>* list) {
  const std::string& from = event.getPublisherName();
  // What this node publishes are its robots' answers, relayed by TakeAnswers already.
  if (from == ros::this_node::getName()) return;
  list->emplace_back(from, *event.getConstMessage());
  if constexpr (std::is_same_v<M, Mission_Status>) NoteStatus(*event.getConstMessage());
  if constexpr (std::is_same_v<M, Mission_Event>) NoteEvent(*event.getConstMessage());
  if constexpr (std::is_same_v<M, New_Mission>) barrier_.OrderArrived(event.getConstMessage()->mission_id);
}

void Simulator::NoteStatus(const Mission_Status& status) {
  if (!params_.lockstep_dispatcher) return;
  const std::uint16_t id = status.mission_id;
  const auto awaits = [this, id](std::uint8_t kind, double delay_s) {
    if (delay_s >= 0.0) barrier_.Await({id, kind});
  };
  switch (status.state) {
    case Mission_Status::LOADING:
      awaits(Mission_Event::LOADED, params_.swarm.loaded_delay_s);
      break;
    case Mission_Status::UNLOADING:
      awaits(Mission_Event::UNLOADED, params_.swarm.unloaded_delay_s);
      break;
    case Mission_Status::DONE:
    case Mission_Status::ABORTED:
    case Mission_Status::REJECTED:
      // The id may be used again by a later mission.
      barrier_.Forget(id);
      break;
    default:
      break;
  }
}

void Simulator::NoteEvent(const Mission_Event& event) {
  if (!params_.lockstep_dispatcher) return;
  barrier_.Seen({event.mission_id, event.event});
}

void Simulator::WaitForDispatcher() {
  const auto holding = [this] {
    return barrier_.EventsAwaited() || barrier_.OrdersMissing(tick_);
  };
  if (!holding()) return;
  // An order or the schedule is due once per run and may wait for the dispatcher's listeners:
  // the start-up timeout; a LOADED / UNLOADED the tick timeout.
  const double timeout_s = barrier_.OrdersMissing(tick_) ? params_.lockstep_start_timeout_s
                                                         : params_.lockstep_timeout_s;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (holding() && Running() && ros::WallTime::now() < deadline) {
    SpinOnce(kPollS);
  }
  if (!holding() || !Running()) return;
  if (barrier_.ScheduleMissing() && tick_ >= 1) {
    ROS_WARN("lockstep tick %llu: no %s from the dispatcher within %.2f s; not waiting for it "
             "any longer", static_cast<unsigned long long>(tick_), names::kMissionSchedule,
             timeout_s);
  }
  for (std::uint16_t id : barrier_.GiveUpOrders(tick_)) {
    ROS_WARN("lockstep tick %llu: the order of scheduled mission %u did not arrive within "
             "%.2f s; not waiting for it any longer", static_cast<unsigned long long>(tick_), id,
             timeout_s);
  }
  for (const auto& key : barrier_.GiveUpEvents()) {
    ROS_WARN("lockstep tick %llu: no %s for mission %u from the dispatcher within %.2f s; "
             "not waiting for it any longer",
             static_cast<unsigned long long>(tick_),
             key.second == Mission_Event::LOADED ? "LOADED" : "UNLOADED", key.first, timeout_s);
  }
}

void Simulator::OnSchedule(const Mission_Schedule::ConstPtr& msg) {
  std::vector<std::pair<std::uint16_t, std::uint64_t>> orders;
  const std::size_t n = std::min(msg->mission_ids.size(), msg->start_ticks.size());
  for (std::size_t i = 0; i < n; ++i) orders.emplace_back(msg->mission_ids[i], msg->start_ticks[i]);
  barrier_.OnSchedule(orders);
}

void Simulator::ReleaseMissions() {
  // In arrival order: what is due enters this tick's relay and the simulator's books (the
  // mission channel, markers) together; the rest waits for its start tick.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pending_missions_.size(); ++i) {
    auto& entry = pending_missions_[i];
    if (entry.second.start_tick > tick_) {
      if (kept != i) pending_missions_[kept] = std::move(entry);
      ++kept;
      continue;
    }
    RegisterMission(entry.second);
    relay_missions_.push_back(std::move(entry));
  }
  pending_missions_.resize(kept);
}

namespace {

template <typename M>
std::vector<M> Sorted(std::vector<std::pair<std::string, M>> list) {
  std::stable_sort(list.begin(), list.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<M> out;
  out.reserve(list.size());
  for (auto& item : list) out.push_back(std::move(item.second));
  return out;
}

}  // namespace

void Simulator::FillRelay(Neighbors* msg) const {
  msg->missions = Sorted(relay_missions_);
  msg->object_updates = Sorted(relay_updates_);
  msg->object_deletes = Sorted(relay_deletes_);
  msg->freezes = Sorted(relay_freezes_);
  msg->continues = Sorted(relay_continues_);
  msg->mission_events = Sorted(relay_events_);
  msg->statuses = Sorted(relay_statuses_);
}

void Simulator::ClearRelay() {
  relay_missions_.clear();
  relay_updates_.clear();
  relay_deletes_.clear();
  relay_freezes_.clear();
  relay_continues_.clear();
  relay_events_.clear();
  relay_statuses_.clear();
}

void Simulator::OnAnswer(std::uint16_t id, const Tick_Answer& answer) {
  if (finished_ || io_.count(id) == 0) return;
  const bool finite = IsFinite(answer.command);
  if (!finite && WallThrottle(&last_bad_cmd_warning_wall_, kWarnPeriodS)) {
    ROS_WARN("lockstep: robot %u answered with a non-finite command; it stands instead", id);
  }
  const auto result =
      barrier_.OnAnswer(id, answer.tick, finite ? ToVelocity(answer.command) : core::Velocity());
  switch (result) {
    case sim::LockstepBarrier::Answer::kAnswer:
    case sim::LockstepBarrier::Answer::kStale:
      // A late answer's command is past, but what it says still holds: relayed a tick late.
      answers_.emplace_back(id, answer);
      break;
    case sim::LockstepBarrier::Answer::kOutside:
      if (io_.at(id).silent) {
        // A robot that let a tick time out answered at last (its late answer): it is waited
        // for again from the next tick on. What it said still holds.
        io_.at(id).silent = false;
        answers_.emplace_back(id, answer);
        ROS_INFO("lockstep: robot %u answers again (tick %llu, its answer to tick %llu)", id,
                 static_cast<unsigned long long>(tick_),
                 static_cast<unsigned long long>(answer.tick));
        break;
      }
      [[fallthrough]];
    case sim::LockstepBarrier::Answer::kUnsolicited:
      if (WallThrottle(&last_unsolicited_warning_wall_, kWarnPeriodS)) {
        ROS_WARN("lockstep: robot %u answered tick %llu, which it was not asked (tick %llu); "
                 "ignored", id, static_cast<unsigned long long>(answer.tick),
                 static_cast<unsigned long long>(tick_));
      }
      break;
  }
}

namespace {

// The relay's sender of a robot's answer: after every node name (they start with '/'), in
// ascending robot id.
std::string AnswerSender(std::uint16_t id) {
  char name[16];
  std::snprintf(name, sizeof(name), "robot_%05u", static_cast<unsigned>(id));
  return name;
}

}  // namespace

void Simulator::TakeAnswers() {
  // By robot id, then in arrival order (a late answer before the robot's current one).
  std::stable_sort(answers_.begin(), answers_.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& entry : answers_) {
    const std::string sender = AnswerSender(entry.first);
    const Tick_Answer& a = entry.second;
    for (const Update_Object& u : a.object_updates) {
      relay_updates_.emplace_back(sender, u);
      sim::UpdateMissionObject(u.mission_id, {u.object_position_x, u.object_position_y}, *world_,
                               &missions_);
      update_pub_.publish(u);
    }
    for (const Robot_Freeze& f : a.freezes) {
      relay_freezes_.emplace_back(sender, f);
      freeze_pub_.publish(f);
    }
    for (const Robot_Continue& c : a.continues) {
      relay_continues_.emplace_back(sender, c);
      continue_pub_.publish(c);
    }
    for (const Delete_Object& d : a.object_deletes) {
      relay_deletes_.emplace_back(sender, d);
      missions_.erase(d.mission_id);
      delete_pub_.publish(d);
    }
    for (const Mission_Status& st : a.statuses) {
      relay_statuses_.emplace_back(sender, st);
      NoteStatus(st);
      status_pub_.publish(st);
    }
    for (const Mission_Status& st : a.progress) progress_pub_.publish(st);
  }
  answers_.clear();
}

void Simulator::PublishRobotList() {
  Robot_Positions list;
  list.tick = tick_;
  for (const auto& entry : world_->robots()) {
    list.robots.push_back(ToRobotPosition(entry.first, entry.second.pose));
  }
  robots_pub_.publish(list);
}

void Simulator::PublishPoses() {
  for (const auto& entry : io_) {
    if (entry.second.pose_subscribers == 0) continue;
    const sim::Robot* robot = world_->Find(entry.first);
    if (robot != nullptr) entry.second.pose.publish(ToPoseMsg(robot->pose, robot->last_velocity));
  }
}

void Simulator::PublishVisualsIfDue() {
  if (visuals_->Due()) visuals_->Publish(*world_, missions_, Stamp());
}

void Simulator::OnSimulatorThread(std::function<void()> call) {
  if (std::this_thread::get_id() == thread_) {
    call();
    return;
  }
  cmd_queue_.addCallback(boost::make_shared<QueuedCall>(std::move(call)));
}

void Simulator::SendCommand(std::uint16_t id, const geometry_msgs::Twist& command) {
  OnSimulatorThread([this, id, command]() { OnCmdVel(id, command); });
}

void Simulator::SendAnswer(std::uint16_t id, const Tick_Answer& answer) {
  OnSimulatorThread([this, id, answer]() { OnAnswer(id, answer); });
}

void Simulator::OnCmdVel(std::uint16_t id, const geometry_msgs::Twist& msg) {
  auto it = io_.find(id);
  if (it == io_.end() || finished_) return;
  const bool finite = IsFinite(msg);
  if (!finite && WallThrottle(&last_bad_cmd_warning_wall_, kWarnPeriodS)) {
    ROS_WARN("simulator: robot %u sent a cmd_vel with a non-finite value; it stands instead", id);
  }
  if (lockstep_ && barrier_.Live(id)) {
    // A lock-step robot's command comes in its answer; a cmd_vel beside it would race it.
    if (WallThrottle(&last_unsolicited_warning_wall_, kWarnPeriodS)) {
      ROS_WARN("lockstep: ignored a cmd_vel for robot %u, which answers its ticks (tick %llu)",
               id, static_cast<unsigned long long>(tick_));
    }
    return;
  }
  // Real time, or a robot outside the lock-step protocol: the command applies at once.
  if (finite) world_->SetCommand(id, ToVelocity(msg), nullptr);
}

bool Simulator::OnSpawn(Spawn::Request& req, Spawn::Response& res) {
  std::string error;
  const core::Pose2 pose{{req.x, req.y}, core::Angle::FromRadians(req.theta)};
  if (!world_->Spawn(req.robot_id, pose, &error)) {
    ROS_WARN("simulator: spawn of robot %u rejected: %s", req.robot_id, error.c_str());
    res.code = Spawn::Response::ERROR;
    res.message = error;
    return true;
  }
  AddRobotIo(req.robot_id);
  PublishRobotList();
  ROS_INFO("simulator: spawned robot %u at (%.3f, %.3f, %.3f rad)", req.robot_id, req.x, req.y,
           req.theta);
  res.code = Spawn::Response::OK;
  res.message = "spawned robot " + std::to_string(req.robot_id);
  return true;
}

bool Simulator::OnKill(Kill::Request& req, Kill::Response& res) {
  if (world_->Find(req.robot_id) == nullptr) {
    res.code = Kill::Response::ERROR;
    res.message = "robot " + std::to_string(req.robot_id) + " does not exist";
    ROS_WARN("simulator: kill rejected: %s", res.message.c_str());
    return true;
  }
  RemoveRobot(req.robot_id);
  PublishRobotList();
  ROS_INFO("simulator: killed robot %u", req.robot_id);
  res.code = Kill::Response::OK;
  res.message = "killed robot " + std::to_string(req.robot_id);
  return true;
}

bool Simulator::OnReset(std_srvs::Empty::Request& /*req*/, std_srvs::Empty::Response& /*res*/) {
  world_->Reset();
  ROS_INFO("simulator: reset %zu robots to their spawn poses", world_->size());
  return true;
}

bool Simulator::OnTeleportAbsolute(std::uint16_t id, TeleportAbsolute::Request& req,
                                   TeleportAbsolute::Response& res) {
  std::string error;
  const core::Pose2 pose{{req.x, req.y}, core::Angle::FromRadians(req.theta)};
  return Reply(world_->TeleportAbsolute(id, pose, &error), "teleport_absolute", id, error, &res);
}

bool Simulator::OnTeleportRelative(std::uint16_t id, TeleportRelative::Request& req,
                                   TeleportRelative::Response& res) {
  std::string error;
  return Reply(world_->TeleportRelative(id, req.linear, req.angular, &error), "teleport_relative",
               id, error, &res);
}

void Simulator::OnPosition(const Robot_Position::ConstPtr& msg) {
  if (msg->type == Robot_Position::TYPE_PHYSICAL) return;  // the world's truth is relayed
  if (!IsFinite(*msg)) {
    if (WallThrottle(&last_bad_position_warning_wall_, kWarnPeriodS)) {
      ROS_WARN("simulator: rejected a Robot_Position of robot %u/%u with a non-finite value",
               msg->robot_id, msg->sub_id);
    }
    return;
  }
  if (msg->type != Robot_Position::TYPE_VIRTUAL && msg->type != Robot_Position::TYPE_STATIST) {
    if (WallThrottle(&last_bad_position_warning_wall_, kWarnPeriodS)) {
      ROS_WARN("simulator: rejected a Robot_Position of robot %u/%u with unknown type %u",
               msg->robot_id, msg->sub_id, msg->type);
    }
    return;
  }
  Robot_Position p = *msg;
  p.angle = static_cast<float>(core::Angle(p.angle).degrees());
  if (p.angle >= 360.0f) p.angle = 0.0f;
  relayed_[RelayKey(p.robot_id, p.sub_id)] = p;
}

void Simulator::OnRobotDelete(const Delete_Robot::ConstPtr& msg) {
  relayed_.erase(RelayKey(msg->robot_id, msg->sub_id));
}

void Simulator::OnMissionNew(const New_Mission::ConstPtr& msg) { RegisterMission(*msg); }

void Simulator::RegisterMission(const New_Mission& order) {
  const std::string why = sim::RegisterMission(ToMissionSpec(order), *world_, &missions_);
  if (!why.empty()) {
    ROS_DEBUG("simulator: ignored New_Mission %u: %s", order.mission_id, why.c_str());
  }
}

void Simulator::OnObjectUpdate(const Update_Object::ConstPtr& msg) {
  sim::UpdateMissionObject(msg->mission_id, {msg->object_position_x, msg->object_position_y},
                           *world_, &missions_);
}

void Simulator::OnObjectDelete(const Delete_Object::ConstPtr& msg) {
  missions_.erase(msg->mission_id);
}

}  // namespace swarm_transport
