#include "swarm_transport/ros/simulator.h"

#include <rosgraph_msgs/Clock.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
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
// The stream of the seed's generator that draws the poses of robots joining by New_Robot.
constexpr std::uint64_t kSpawnStream = 0x737061776eULL;  // "spawn"
// Queue sizes. /flock/position: every robot publishes every tick and only virtual copies /
// statists matter, so it must hold a whole swarm's tick. /flock/positions: the recorder must
// see every lock-step tick.
constexpr std::uint32_t kPositionQueue = 10000;
constexpr std::uint32_t kPositionsQueue = 100;
// Lock-step runs thousands of ticks per second in one process (deploy:=host_sim): a recorder
// or a runner that falls behind for a moment must not lose frames (a sample would move to a
// later tick). Memory is used only while a subscriber lags.
constexpr std::uint32_t kLockstepPositionsQueue = 10000;
constexpr std::uint32_t kMissionQueue = 100;
// Period of the idle loop after the last lock-step tick and of the start wait (s).
constexpr double kIdleS = 0.01;
// At most one warning of a kind per this many wall seconds (see WallThrottle).
constexpr double kWarnPeriodS = 5.0;

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

volatile std::sig_atomic_t Simulator::stop_requested_ = 0;

Simulator::Simulator(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh) {}

void Simulator::RequestStop() { stop_requested_ = 1; }

bool Simulator::Running() { return stop_requested_ == 0 && ros::ok(); }

bool Simulator::Initialize() {
  thread_ = std::this_thread::get_id();
  std::string error;
  bool ok = ReadSimulatorParams(nh_, private_nh_, direct_ != nullptr, &params_, &error);
  if (ok) {
    world_ = std::make_unique<sim::World2D>(WorldParamsOf(params_));
    ok = sim::PlaceInitialRobots(params_.placement, params_.swarm.seed, params_.placement_file,
                                 &params_.robots, world_.get(), &error);
    if (!ok && error.empty()) error = "the initial robots do not fit the arena";
  }
  if (ok && !params_.events_file.empty()) {
    std::vector<TimedEvent> events;
    ok = ReadEventsFile(params_.events_file, &events, &error);
    if (ok) {
      ROS_INFO("simulator: %zu timed event(s) from %s", events.size(),
               params_.events_file.c_str());
      events_ = std::make_unique<EventSchedule>(std::move(events));
    } else {
      error = "~events_file: " + error;
    }
  }
  if (!ok) {
    ROS_FATAL("simulator: invalid parameters: %s", error.c_str());
    return false;
  }
  lockstep_ = params_.clock == core::Clock::kLockstep;
  radio_follows_range_ = !private_nh_.hasParam("radio_range_m");
  tuning_ = std::make_unique<TuningRelay>(params_.swarm);
  radio_rng_ = std::make_unique<core::Rng>(params_.swarm.seed, sim::kRadioLossStream);
  radio_ = std::make_unique<sim::Radio>(RadioParamsOf(params_), radio_rng_.get());
  spawn_rng_ = std::make_unique<core::Rng>(params_.swarm.seed, kSpawnStream);
  RobotLinkHandlers handlers;
  handlers.cmd_vel = [this](std::uint16_t id, const geometry_msgs::Twist& m) { OnCmdVel(id, m); };
  handlers.answer = [this](std::uint16_t id, const Tick_Answer& m) { OnAnswer(id, m); };
  handlers.teleport_absolute = [this](std::uint16_t id, TeleportAbsolute::Request& req,
                                      TeleportAbsolute::Response& res) {
    return OnTeleportAbsolute(id, req, res);
  };
  handlers.teleport_relative = [this](std::uint16_t id, TeleportRelative::Request& req,
                                      TeleportRelative::Response& res) {
    return OnTeleportRelative(id, req, res);
  };
  links_ = std::make_unique<RobotLinks>(nh_, &cmd_queue_, direct_, lockstep_,
                                        params_.pose_topics, std::move(handlers));
  if (lockstep_) {
    LockstepHooks hooks;
    hooks.running = &Simulator::Running;
    hooks.spin = [this](double wait_s) { SpinOnce(wait_s); };
    hooks.spin_robots = [this] { SpinRobots(); };
    hooks.visuals = [this] { PublishVisualsIfDue(); };
    hooks.books = [this](const Tick_Answer& a) {
      for (const Update_Object& u : a.object_updates) {
        sim::UpdateMissionObject(u.mission_id, {u.object_position_x, u.object_position_y},
                                 *world_, &missions_);
      }
      for (const Delete_Object& d : a.object_deletes) missions_.erase(d.mission_id);
    };
    session_ = std::make_unique<LockstepSession>(nh_, params_, links_.get(), &cmd_queue_,
                                                 std::move(hooks));
  }
  Connect();
  for (const auto& entry : world_->robots()) AddRobot(entry.first);
  PublishRobotList();

  bool use_sim_time = false;
  nh_.getParam("/use_sim_time", use_sim_time);
  if (!lockstep_ && use_sim_time) {
    ROS_WARN("simulator: realtime clock but /use_sim_time is true: nobody publishes /clock");
  }
  ROS_INFO(
      "simulator: %zu robots (%s placement), %s clock, tick %.3f s, step %.3f s, "
      "arena %.3f m, radius %.3f m, radio range %.3f m, loss %.2f, seed %llu",
      world_->size(), core::PlacementName(params_.placement), core::ClockName(params_.clock),
      params_.swarm.tick_period_s, params_.integration_step_s,
      params_.swarm.flocking.world_size_m, params_.swarm.flocking.robot_radius_m,
      params_.radio_range_m, params_.radio_loss,
      static_cast<unsigned long long>(params_.swarm.seed));
  return true;
}

void Simulator::Connect() {
  objects_pub_ = nh_.advertise<Mission_Objects>(
      names::kObjects, lockstep_ ? kLockstepPositionsQueue : kPositionsQueue);
  // Latched: a late subscriber (a test after the last lock-step tick) still gets the state.
  positions_pub_ = nh_.advertise<Robot_Positions>(
      names::kPositions, lockstep_ ? kLockstepPositionsQueue : kPositionsQueue, true);
  robots_pub_ = nh_.advertise<Robot_Positions>(names::kRobots, 1, true);
  if (lockstep_) clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>(kClockTopic, 10);
  sim::VisualsParams visuals;
  visuals.rate_hz = params_.markers_rate_hz;
  visuals.tf = params_.tf;
  visuals.range_circles = params_.range_circles;
  visuals.trail_ticks = params_.trail_ticks;
  visuals.local_range_m = params_.swarm.flocking.local_range_m;
  visuals.danger_zones = params_.swarm.danger_zones;
  visuals_ = std::make_unique<sim::Visuals>(nh_, std::move(visuals));
  diagnostics_ = std::make_unique<NodeDiagnostics>(
      nh_, "swarm_transport: simulator" + std::string(direct_ ? " (in robot_host)" : ""));
  spawn_srv_ = nh_.advertiseService(names::kSpawn, &Simulator::OnSpawn, this);
  kill_srv_ = nh_.advertiseService(names::kKill, &Simulator::OnKill, this);
  reset_srv_ = nh_.advertiseService(names::kReset, &Simulator::OnReset, this);
  hold_srv_ = private_nh_.advertiseService("hold", &Simulator::OnHold, this);
  // /flock/position also carries every robot's own position each tick; we only keep virtual
  // copies and statists, but the queue must hold a whole tick of the swarm.
  position_sub_ = nh_.subscribe(names::kPosition, kPositionQueue, &Simulator::OnPosition, this,
                                ros::TransportHints().tcpNoDelay());
  robot_new_sub_ = nh_.subscribe(names::kRobotNew, kMissionQueue, &Simulator::OnRobotNew, this);
  robot_delete_sub_ =
      nh_.subscribe(names::kRobotDelete, kMissionQueue, &Simulator::OnRobotDelete, this);
  if (!lockstep_) {
    // Lock-step takes orders in through the relay, at the tick the robots take them.
    mission_new_sub_ =
        nh_.subscribe(names::kMissionNew, kMissionQueue, &Simulator::OnMissionNew, this);
  }
  object_update_sub_ =
      nh_.subscribe(names::kObjectUpdate, kMissionQueue, &Simulator::OnObjectUpdate, this);
  // Each mission's phase, for the status line in rviz (lock-step: this node's own relay).
  status_sub_ = nh_.subscribe(names::kMissionStatus, kMissionQueue, &Simulator::OnMissionStatus,
                              this);
  object_delete_sub_ =
      nh_.subscribe(names::kObjectDelete, kMissionQueue, &Simulator::OnObjectDelete, this);
  if (events_ && !lockstep_) {
    // Real time: a timed event goes out as this node's message (robots take it as relayed).
    event_freeze_pub_ = nh_.advertise<Robot_Freeze>(names::kFreeze, kMissionQueue);
    event_continue_pub_ = nh_.advertise<Robot_Continue>(names::kContinue, kMissionQueue);
    event_update_pub_ = nh_.advertise<Update_Object>(names::kObjectUpdate, kMissionQueue);
    event_signal_pub_ = nh_.advertise<Mission_Event>(names::kMissionEvent, kMissionQueue);
  }
  if (lockstep_) session_->Connect();
  tuning_pub_ = nh_.advertise<Flocking_Tuning>(names::kTuning, 1, true);
  tuning_server_ = std::make_unique<FlockingTuningServer>(private_nh_, tuning_.get());
}

void Simulator::AddRobot(std::uint16_t id) {
  links_->Add(id);
  if (session_) session_->AddRobot(id);
}

void Simulator::RemoveRobot(std::uint16_t id) {
  world_->Kill(id, nullptr);
  links_->Remove(id);
  if (session_) session_->RemoveRobot(id);
  if (direct_ != nullptr && direct_->Hosts(id)) direct_->Release(id);
  relayed_.EraseCopiesOf(id);  // its virtual copies die with it
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
  if (links_) links_->Shutdown();
  position_sub_.shutdown();
  robot_new_sub_.shutdown();
  robot_delete_sub_.shutdown();
  mission_new_sub_.shutdown();
  if (session_) session_->Shutdown();
  object_update_sub_.shutdown();
  status_sub_.shutdown();
  object_delete_sub_.shutdown();
  spawn_srv_.shutdown();
  kill_srv_.shutdown();
  reset_srv_.shutdown();
  hold_srv_.shutdown();
  positions_pub_.shutdown();
  clock_pub_.shutdown();
  tuning_server_.reset();
  tuning_pub_.shutdown();
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
      ApplyDueEvents();
      PublishRadio();
      visuals_->Record(*world_);
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

void Simulator::ApplyAnswers() {
  for (const auto& entry : *links_) {
    if (!session_->Live(entry.first)) continue;
    world_->SetCommand(entry.first, session_->CommandOf(entry.first), nullptr);
  }
}

void Simulator::RunLockstep() {
  session_->WaitForStart(positions_pub_, robots_pub_);
  const ros::WallTime started = ros::WallTime::now();
  const std::uint64_t max_ticks = static_cast<std::uint64_t>(params_.lockstep_max_ticks);
  ros::WallTime started_pacing = started;
  while (Running() && (max_ticks == 0 || tick_ < max_ticks)) {
    // Pacing counts from the start without the time held.
    started_pacing += HoldIfAsked();
    if (!Running()) break;
    tick_begun_ = true;
    session_->BeginTick(tick_);
    ApplyDueEvents();
    PublishClock();
    PublishRadio();
    PublishPoses();
    session_->WaitForAnswers(tick_);
    // All answers of this tick apply together: the result does not depend on arrival order.
    ApplyAnswers();
    world_->Step(params_.swarm.tick_period_s);
    ++tick_;
    tick_begun_ = false;
    visuals_->Record(*world_);
    if (params_.real_time_factor > 0.0) {
      // Paced: tick k ends no earlier than k * tick_period / factor wall seconds after the
      // start (a late tick is not made up for by rushing the next ones).
      const ros::WallTime due =
          started_pacing + ros::WallDuration(static_cast<double>(tick_) * params_.swarm.tick_period_s /
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
  session_->Finish();  // no Neighbors: nobody is asked to answer
  PublishRadio();
  PublishPoses();
  Idle();
}

ros::WallDuration Simulator::HoldIfAsked() {
  const ros::WallTime since = ros::WallTime::now();
  if (hold_at_ == 0 || tick_ < hold_at_) return ros::WallDuration(0.0);
  holding_ = true;
  ROS_INFO("simulator: holding before tick %llu (~hold with tick 0 goes on)",
           static_cast<unsigned long long>(tick_));
  while (Running() && hold_at_ != 0 && tick_ >= hold_at_) {
    SpinOnce(kIdleS);
    PublishVisualsIfDue();
  }
  holding_ = false;
  ROS_INFO("simulator: going on at tick %llu", static_cast<unsigned long long>(tick_));
  return ros::WallTime::now() - since;
}

bool Simulator::OnHold(Hold::Request& req, Hold::Response& res) {
  res.current_tick = tick_;
  res.code = Hold::Response::ERROR;
  if (!lockstep_) {
    res.message = "~hold is for the lock-step clock only";
  } else if (finished_) {
    res.message = "the run is over (last tick done)";
  } else if (req.tick == 0) {
    hold_at_ = 0;
    res.code = Hold::Response::OK;
    res.message = "going on";
  } else if (req.tick < tick_ || (req.tick == tick_ && tick_begun_ && !holding_)) {
    res.message = "tick " + std::to_string(req.tick) + " has begun already (now at tick " +
                  std::to_string(tick_) + "): ask for a later one";
  } else {
    hold_at_ = req.tick;
    res.code = Hold::Response::OK;
    res.holding = holding_ && tick_ == req.tick;
    res.message = (res.holding ? "holding before tick " : "will hold before tick ") +
                  std::to_string(req.tick);
  }
  if (res.code != Hold::Response::OK) ROS_WARN("simulator: ~hold refused: %s", res.message.c_str());
  return true;
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

void Simulator::BeginTuningRound() {
  const std::optional<Flocking_Tuning> tuned = tuning_->BeginRound(tick_);
  if (!tuned) return;
  const double range_m = tuned->local_range_m;
  if (radio_follows_range_) {
    params_.radio_range_m = range_m;
    radio_->set_range_m(range_m);
  }
  visuals_->SetLocalRange(range_m);
  tuning_pub_.publish(*tuned);
  ROS_INFO("simulator: flocking tuning %u from tick %llu: free_will_deg %g, cohesion %g, "
           "local_range_m %g, speed_m_per_tick %g, radio range %g m",
           tuned->generation, static_cast<unsigned long long>(tuned->tick),
           tuned->free_will_deg, tuned->cohesion, tuned->local_range_m,
           tuned->speed_m_per_tick, params_.radio_range_m);
}

void Simulator::PublishRadio() {
  // Not in the final round after the last lock-step tick: nobody acts on it.
  if (!finished_) BeginTuningRound();
  if (lockstep_) {
    // The orders due by this tick enter its relay and the simulator's books together (the
    // mission channel, markers); the rest wait for their start tick.
    for (const New_Mission& order : session_->ReleaseOrders(tick_)) RegisterMission(order);
  }
  const double sim_time = SimTime();
  const auto& robots = world_->robots();
  std::vector<Robot_Position> truth;
  truth.reserve(robots.size());
  for (const auto& entry : robots) truth.push_back(ToRobotPosition(entry.first, entry.second.pose));
  // Robots that do not answer their ticks (dead, hung, not connected yet) are silent on the
  // radio: their peers lose them (issue 11). Directly linked robots always answer.
  std::set<std::uint16_t> quiet;
  for (const auto& entry : *links_) {
    if (entry.second.direct) continue;
    const bool answering =
        lockstep_ ? session_->Live(entry.first) : entry.second.neighbors_subscribers > 0;
    if (!answering) quiet.insert(entry.first);
  }
  radio_->Begin(*world_, relayed_.Extras(), missions_, quiet);
  // Virtual copies are relayed at their owner's true pose, the others where announced.
  const std::vector<Robot_Position> relayed = relayed_.AtOwners(radio_->extra_owner(), truth);

  sim::RadioRound round;
  if (lockstep_) session_->StartRound(tick_);
  std::size_t i = 0;
  for (auto robot = robots.begin(); robot != robots.end(); ++robot, ++i) {
    RobotLink* link = links_->Find(robot->first);
    if (link == nullptr) continue;
    if (!(lockstep_ ? session_->Live(robot->first) : link->Listening())) continue;
    radio_->Hear(i, &round);
    Neighbors msg = RadioRoundMessage(tick_, sim_time, robot->second, round, truth, relayed);
    if (lockstep_) session_->FillRound(&msg);
    tuning_->Fill(&msg);
    link->Deliver(robot->first, direct_, std::move(msg));
    if (lockstep_) session_->Asked(robot->first);
  }

  if (lockstep_) session_->EndRound();
  Robot_Positions all;
  all.tick = tick_;
  all.sim_time = sim_time;
  all.robots = std::move(truth);
  positions_pub_.publish(all);
  if (objects_pub_.getNumSubscribers() > 0) {
    Mission_Objects objects;
    objects.tick = tick_;
    for (const auto& entry : missions_) {
      const sim::LiveMission& m = entry.second;
      if (m.object_size.x <= 0.0 && m.object_size.y <= 0.0) continue;  // leader-only
      objects.mission_ids.push_back(entry.first);
      objects.x.push_back(static_cast<float>(m.object_position.x));
      objects.y.push_back(static_cast<float>(m.object_position.y));
      objects.size_x.push_back(static_cast<float>(m.object_size.x));
      objects.size_y.push_back(static_cast<float>(m.object_size.y));
    }
    objects_pub_.publish(objects);
  }
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
  for (const auto& entry : *links_) {
    if (entry.second.pose_subscribers == 0) continue;
    const sim::Robot* robot = world_->Find(entry.first);
    if (robot != nullptr) entry.second.pose.publish(ToPoseMsg(robot->pose, robot->last_velocity));
  }
}

void Simulator::PublishVisualsIfDue() {
  if (visuals_->Due()) visuals_->Publish(*world_, missions_, Stamp(), tick_);
  diagnostics_->PublishIfDue([this](NodeStatus* s) {
    const std::size_t robots = world_->size();
    const std::size_t live = session_ ? session_->LiveCount() : robots;
    s->message = std::string(core::ClockName(params_.clock)) + ", tick " + std::to_string(tick_) +
                 ", " + std::to_string(robots) + " robots";
    if (lockstep_ && !finished_ && live < robots) {
      // Robots that do not answer their ticks (not connected yet, hung, dead).
      s->level = diagnostic_msgs::DiagnosticStatus::WARN;
      s->message += ", " + std::to_string(robots - live) + " not answering";
    }
    if (finished_) s->message += " (last tick done)";
    if (holding_) s->message += " (held: ~hold)";
    s->Add("tick", tick_);
    s->Add("sim_time_s", SimTime());
    s->Add("robots", static_cast<std::uint64_t>(robots));
    s->Add("answering", static_cast<std::uint64_t>(live));
    s->Add("missions", static_cast<std::uint64_t>(missions_.size()));
    s->Add("flocking_tuning", static_cast<std::uint64_t>(tuning_->generation()));
  });
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

void Simulator::OnAnswer(std::uint16_t id, const Tick_Answer& answer) {
  if (finished_ || links_->Find(id) == nullptr) return;
  session_->OnAnswer(id, answer, tick_);
}

void Simulator::OnCmdVel(std::uint16_t id, const geometry_msgs::Twist& msg) {
  if (links_->Find(id) == nullptr || finished_) return;
  const bool finite = IsFinite(msg);
  if (!finite && WallThrottle(&last_bad_cmd_warning_wall_, kWarnPeriodS)) {
    ROS_WARN("simulator: robot %u sent a cmd_vel with a non-finite value; it stands instead", id);
  }
  if (lockstep_ && session_->Live(id)) {
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

void Simulator::ApplyDueEvents() {
  if (!events_) return;
  for (const TimedEvent& e : events_->Due(tick_)) {
    switch (e.kind) {
      case TimedEvent::Kind::kFreeze: {
        Robot_Freeze msg;
        msg.robot_index_from = e.from;
        msg.robot_index_to = e.to;
        if (session_) session_->Inject(msg); else event_freeze_pub_.publish(msg);
        break;
      }
      case TimedEvent::Kind::kContinue: {
        Robot_Continue msg;
        msg.robot_index_from = e.from;
        msg.robot_index_to = e.to;
        if (session_) session_->Inject(msg); else event_continue_pub_.publish(msg);
        break;
      }
      case TimedEvent::Kind::kObjectUpdate: {
        Update_Object msg;
        msg.mission_id = e.mission;
        msg.object_position_x = static_cast<float>(e.x);
        msg.object_position_y = static_cast<float>(e.y);
        sim::UpdateMissionObject(e.mission, {e.x, e.y}, *world_, &missions_);
        if (session_) session_->Inject(msg); else event_update_pub_.publish(msg);
        break;
      }
      case TimedEvent::Kind::kSignal: {
        Mission_Event msg;
        msg.mission_id = e.mission;
        msg.event = e.signal;
        msg.not_before_tick = e.tick;
        if (session_) session_->Inject(msg); else event_signal_pub_.publish(msg);
        break;
      }
      case TimedEvent::Kind::kKill:
        if (world_->Find(e.robot) == nullptr) {
          ROS_WARN("simulator: timed kill of robot %u at tick %llu: no such robot", e.robot,
                   static_cast<unsigned long long>(tick_));
          break;
        }
        RemoveRobot(e.robot);
        PublishRobotList();
        ROS_INFO("simulator: killed robot %u (timed event, tick %llu)", e.robot,
                 static_cast<unsigned long long>(tick_));
        break;
      case TimedEvent::Kind::kSpawn:
        SpawnRobot(e.robot, {{e.x, e.y}, core::Angle(e.theta_deg)});
        break;
      case TimedEvent::Kind::kStatist: {
        Robot_Position statist;
        statist.robot_id = e.robot;
        statist.sub_id = e.sub_id;
        statist.type = Robot_Position::TYPE_STATIST;
        statist.pos_x = static_cast<float>(e.x);
        statist.pos_y = static_cast<float>(e.y);
        relayed_.Take(statist);
        break;
      }
      case TimedEvent::Kind::kRemoveStatist:
        relayed_.Erase(e.robot, e.sub_id);
        break;
    }
  }
}

std::string Simulator::SpawnRobot(std::uint16_t id, const core::Pose2& pose) {
  std::string error;
  if (!world_->Spawn(id, pose, &error)) {
    ROS_WARN("simulator: spawn of robot %u rejected: %s", id, error.c_str());
    return error;
  }
  PublishRobotList();  // first: a robot started now finds itself listed
  // A host of many robots that runs this simulator starts the robot itself.
  if (direct_ != nullptr && !direct_->Hosts(id)) direct_->Adopt(id);
  AddRobot(id);
  ROS_INFO("simulator: spawned robot %u at (%.3f, %.3f, %.1f deg)", id, pose.position.x,
           pose.position.y, pose.heading.degrees());
  return "";
}

bool Simulator::OnSpawn(Spawn::Request& req, Spawn::Response& res) {
  const core::Pose2 pose{{req.x, req.y}, core::Angle::FromRadians(req.theta)};
  const std::string error = SpawnRobot(req.robot_id, pose);
  if (!error.empty()) {
    res.code = Spawn::Response::ERROR;
    res.message = error;
    return true;
  }
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
  const std::string why = relayed_.Take(*msg);
  if (!why.empty() && WallThrottle(&last_bad_position_warning_wall_, kWarnPeriodS)) {
    ROS_WARN("simulator: rejected a Robot_Position of robot %u/%u: %s", msg->robot_id,
             msg->sub_id, why.c_str());
  }
}

void Simulator::OnRobotNew(const New_Robot::ConstPtr& msg) {
  if (msg->type != Robot_Position::TYPE_PHYSICAL) {
    ROS_DEBUG("simulator: New_Robot %u/%u of type %u: it joins by announcing itself on %s",
              msg->robot_id, msg->sub_id, msg->type, names::kPosition);
    return;
  }
  if (world_->Find(msg->robot_id) != nullptr) {
    ROS_INFO("simulator: New_Robot %u: it is in the swarm already", msg->robot_id);
    return;
  }
  core::Pose2 pose;
  if (!sim::FreePose(*world_, spawn_rng_.get(), &pose)) {
    ROS_WARN("simulator: New_Robot %u rejected: no free place in the arena", msg->robot_id);
    return;
  }
  SpawnRobot(msg->robot_id, pose);
}

void Simulator::OnRobotDelete(const Delete_Robot::ConstPtr& msg) {
  if (relayed_.Erase(msg->robot_id, msg->sub_id)) return;
  if (msg->sub_id == 0 && world_->Find(msg->robot_id) != nullptr) {
    RemoveRobot(msg->robot_id);
    PublishRobotList();
    ROS_INFO("simulator: Delete_Robot %u: the robot left the swarm", msg->robot_id);
    return;
  }
  if (WallThrottle(&last_bad_position_warning_wall_, kWarnPeriodS)) {
    ROS_WARN("simulator: Delete_Robot %u/%u: no such robot, virtual copy or statist",
             msg->robot_id, msg->sub_id);
  }
}

// Real time: the mission mirror (the radio's mission channel, markers) follows what the robots
// act on, with the robots' rules (core::MayOrder, core::MayReport).
void Simulator::OnMissionNew(const ros::MessageEvent<New_Mission const>& event) {
  if (!core::MayOrder(params_.swarm.admission, SenderOf(event.getPublisherName()))) return;
  RegisterMission(*event.getConstMessage());
}

void Simulator::RegisterMission(const New_Mission& order) {
  const std::string why = sim::RegisterMission(ToMissionSpec(order), *world_, &missions_);
  if (!why.empty()) {
    ROS_DEBUG("simulator: ignored New_Mission %u: %s", order.mission_id, why.c_str());
  }
}

void Simulator::OnObjectUpdate(const ros::MessageEvent<Update_Object const>& event) {
  const Update_Object& msg = *event.getConstMessage();
  if (!MayReport(msg.mission_id, event.getPublisherName())) return;
  sim::UpdateMissionObject(msg.mission_id, {msg.object_position_x, msg.object_position_y},
                           *world_, &missions_);
}

void Simulator::OnObjectDelete(const ros::MessageEvent<Delete_Object const>& event) {
  if (!MayReport(event.getConstMessage()->mission_id, event.getPublisherName())) return;
  missions_.erase(event.getConstMessage()->mission_id);
}

void Simulator::OnMissionStatus(const ros::MessageEvent<Mission_Status const>& event) {
  const Mission_Status& msg = *event.getConstMessage();
  auto it = missions_.find(msg.mission_id);
  // A REJECTED names an order refused, which may carry a live mission's id (a duplicate).
  if (it == missions_.end() || msg.state >= Mission_Status::REJECTED ||
      !MayReport(msg.mission_id, event.getPublisherName())) {
    return;
  }
  it->second.phase = std::max<int>(it->second.phase, msg.state);
}

bool Simulator::MayReport(std::uint16_t mission_id, const std::string& publisher) const {
  const core::Sender from = SenderOf(publisher);
  const auto it = missions_.find(mission_id);
  if (from.kind != core::SenderKind::kRobot || it == missions_.end()) {
    return core::MayReport(nullptr, from);
  }
  const std::vector<std::uint16_t>& members = it->second.members;
  return std::binary_search(members.begin(), members.end(), from.robot_id);
}

}  // namespace swarm_transport
