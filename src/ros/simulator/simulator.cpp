#include "swarm_transport/ros/simulator/simulator.h"

#include <rosgraph_msgs/Clock.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <set>
#include <type_traits>

#include "swarm_transport/Pose.h"
#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/graph.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

constexpr char kClockTopic[] = "/clock";
// Queue sizes. /flock/position: every robot publishes every tick and only virtual copies /
// statists matter, so it must hold a whole swarm's tick. /flock/world_poses: the recorder must
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
  std::vector<TimedEvent> events;
  if (ok && !params_.events_file.empty()) {
    ok = ReadEventsFile(params_.events_file, &events, &error);
    if (ok) {
      ROS_INFO("simulator: %zu timed event(s) from %s", events.size(), params_.events_file.c_str());
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
  tuning_ = std::make_unique<LiveTuning>(params_.swarm);
  radio_rng_ = std::make_unique<core::Rng>(params_.swarm.seed, sim::kRadioLossStream);
  radio_ = std::make_unique<sim::Radio>(RadioParamsOf(params_), radio_rng_.get());
  RobotLinkHandlers handlers;
  handlers.cmd_vel = [this](std::uint16_t id, const geometry_msgs::Twist& m) { OnCmdVel(id, m); };
  handlers.answer = [this](std::uint16_t id, const Tick_Answer& m) { OnAnswer(id, ToAnswer(m)); };
  handlers.teleport_absolute = [this](std::uint16_t id, TeleportAbsolute::Request& req,
                                      TeleportAbsolute::Response& res) {
    return roster_->OnTeleportAbsolute(id, req, res);
  };
  handlers.teleport_relative = [this](std::uint16_t id, TeleportRelative::Request& req,
                                      TeleportRelative::Response& res) {
    return roster_->OnTeleportRelative(id, req, res);
  };
  links_ = std::make_unique<RobotLinks>(nh_, &cmd_queue_, direct_, lockstep_, params_.pose_topics,
                                        std::move(handlers));
  missions_ = std::make_unique<MissionMirror>(params_.swarm.admission, world_.get());
  engine_ = std::make_unique<sim::LockstepEngine>(world_.get(), radio_.get(),
                                                  missions_->mutable_missions());
  if (lockstep_) {
    LockstepHooks hooks;
    hooks.running = &Simulator::Running;
    hooks.spin = [this](double wait_s) { SpinOnce(wait_s); };
    hooks.spin_robots = [this] { SpinRobots(); };
    hooks.visuals = [this] { PublishVisualsIfDue(); };
    session_ = std::make_unique<LockstepSession>(nh_, params_, links_.get(), &cmd_queue_,
                                                 engine_.get(), std::move(hooks));
  }
  roster_ = std::make_unique<RobotRoster>(world_.get(), links_.get(), session_.get(), direct_,
                                          params_.swarm.seed, &tick_);
  if (!params_.events_file.empty()) {
    events_ = std::make_unique<EventPlayer>(std::move(events), session_.get(), roster_.get(),
                                            missions_.get());
  }
  hold_ = std::make_unique<LockstepHold>(lockstep_, &tick_, &finished_,
                                         static_cast<std::uint64_t>(params_.hold_at));
  Connect();
  for (const auto& entry : world_->robots()) roster_->Add(entry.first);
  roster_->PublishList();

  bool use_sim_time = false;
  nh_.getParam("/use_sim_time", use_sim_time);
  if (!lockstep_ && use_sim_time) {
    ROS_WARN("simulator: realtime clock but /use_sim_time is true: nobody publishes /clock");
  }
  ROS_INFO(
      "simulator: %zu robots (%s placement), %s clock, tick %.3f s, step %.3f s, "
      "arena %.3f m, radius %.3f m, radio range %.3f m, loss %.2f, seed %llu",
      world_->size(), core::PlacementName(params_.placement), core::ClockName(params_.clock),
      params_.swarm.tick_period_s, params_.integration_step_s, params_.swarm.flocking.world_size_m,
      params_.swarm.flocking.robot_radius_m, params_.radio_range_m, params_.radio_loss,
      static_cast<unsigned long long>(params_.swarm.seed));
  return true;
}

void Simulator::Connect() {
  const std::uint32_t positions_queue = lockstep_ ? kLockstepPositionsQueue : kPositionsQueue;
  // Latched: a late subscriber (a test after the last lock-step tick) still gets the state.
  positions_pub_ = nh_.advertise<Robot_Positions>(names::kWorldPoses, positions_queue, true);
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
  roster_->Connect(nh_, kPositionQueue, kMissionQueue);
  missions_->Connect(nh_, lockstep_, positions_queue);
  hold_->Connect(private_nh_);
  if (events_) events_->Connect(nh_, kMissionQueue);
  if (lockstep_) session_->Connect();
  tuning_->Connect(nh_, private_nh_, params_.radio_loss);
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
  if (roster_) roster_->Shutdown();
  if (session_) session_->Shutdown();
  if (missions_) missions_->Shutdown();
  if (hold_) hold_->Shutdown();
  positions_pub_.shutdown();
  clock_pub_.shutdown();
  if (tuning_) tuning_->Shutdown();
  if (visuals_) visuals_->Shutdown();
}

void Simulator::SpinOnce(double wait_s) {
  SpinRobots();
  direct_commands_.TakeAll(
      [this](std::uint16_t id, const geometry_msgs::Twist& command) { OnCmdVel(id, command); });
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
      // Overlaps pushed apart once per round, before the radio samples the world (lock-step: once
      // per tick), not every 10 ms step: no robot perceives between rounds (docs/scale.md).
      world_->ResolveContacts();
      if (events_) events_->ApplyDue(tick_);
      PublishRadio();
      visuals_->Record(*world_);
      ++tick_;
      next_radio += tick;
      if (next_radio < now) next_radio = now + tick;  // fell behind: skip, do not burst
    }
    world_->Step(params_.integration_step_s, /*resolve_contacts=*/false);
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
  session_->WaitForStart(positions_pub_, roster_->list_publisher());
  const ros::WallTime started = ros::WallTime::now();
  const std::uint64_t max_ticks = static_cast<std::uint64_t>(params_.lockstep_max_ticks);
  ros::WallTime started_pacing = started;
  while (Running() && (max_ticks == 0 || tick_ < max_ticks)) {
    // Pacing counts from the start without the time held.
    started_pacing += hold_->HoldIfAsked(&Simulator::Running, [this] {
      SpinOnce(kIdleS);
      PublishVisualsIfDue();
    });
    if (!Running()) break;
    hold_->BeginTick();
    session_->BeginTick(tick_);
    ApplyRecruitStatists();
    if (events_) events_->ApplyDue(tick_);
    PublishClock();
    PublishRadio();
    PublishPoses();
    session_->WaitForAnswers(tick_);
    // All answers of this tick apply together: the result does not depend on arrival order.
    ApplyAnswers();
    world_->Step(params_.swarm.tick_period_s);
    ++tick_;
    hold_->EndTick();
    visuals_->Record(*world_);
    if (params_.real_time_factor > 0.0) {
      // Paced: tick k ends no earlier than k * tick_period / factor wall seconds after the
      // start (a late tick is not made up for by rushing the next ones).
      const ros::WallTime due = started_pacing + ros::WallDuration(static_cast<double>(tick_) *
                                                                   params_.swarm.tick_period_s /
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
  if (const std::optional<double> loss = tuning_->TakeRadioLoss()) {
    params_.radio_loss = *loss;
    radio_->set_loss(*loss);
    ROS_INFO("simulator: radio loss %g from tick %llu", *loss,
             static_cast<unsigned long long>(tick_));
  }
  const std::optional<core::TuningGeneration> tuned = tuning_->BeginRound(tick_);
  if (!tuned) return;
  const core::FlockingTuning& t = tuned->tuning;
  const double range_m = t.local_range_m;
  if (radio_follows_range_) {
    params_.radio_range_m = range_m;
    radio_->set_range_m(range_m);
  }
  visuals_->SetLocalRange(range_m);
  ROS_INFO(
      "simulator: flocking tuning %u from tick %llu: free_will_deg %g, cohesion %g, "
      "local_range_m %g, speed_m_per_tick %g, radio range %g m",
      tuned->generation, static_cast<unsigned long long>(tuned->tick), t.free_will_deg, t.cohesion,
      t.local_range_m, t.speed_m_per_tick, params_.radio_range_m);
}

void Simulator::PublishRadio() {
  // Not in the final round after the last lock-step tick: nobody acts on it.
  if (!finished_) BeginTuningRound();
  if (lockstep_) {
    // The orders due by this tick enter its relay and the simulator's books together (the
    // mission channel, markers); the rest wait for their start tick.
    for (const auto& refused : engine_->ReleaseOrders(tick_)) {
      ROS_DEBUG("simulator: ignored the order of mission %u: %s", refused.first.id,
                refused.second.c_str());
    }
  }
  const auto& robots = world_->robots();
  // Robots that do not answer their ticks (dead, hung, not connected yet) are silent on the
  // radio: their peers lose them (issue 11). Directly linked robots always answer.
  std::set<std::uint16_t> quiet;
  for (const auto& entry : *links_) {
    if (entry.second.direct) continue;
    const bool answering =
        lockstep_ ? session_->Live(entry.first) : entry.second.neighbors_subscribers > 0;
    if (!answering) quiet.insert(entry.first);
  }
  engine_->BeginRound(tick_, SimTime(), &roster_->relayed(), quiet);

  if (lockstep_) session_->StartRound(tick_);
  std::size_t i = 0;
  for (auto robot = robots.begin(); robot != robots.end(); ++robot, ++i) {
    RobotLink* link = links_->Find(robot->first);
    if (link == nullptr) continue;
    if (!(lockstep_ ? session_->Live(robot->first) : link->Listening())) continue;
    if (lockstep_) {
      session_->Round(i, robot->first, &round_);
    } else {
      engine_->Round(i, false, &round_);  // real time relays nothing: its robots hear the topics
    }
    tuning_->Fill(&round_);
    link->Deliver(robot->first, direct_, ToNeighbors(round_));
    if (lockstep_) session_->Asked(robot->first);
  }

  if (lockstep_) session_->EndRound();
  if (direct_ != nullptr) direct_->EndRound();
  Robot_Positions all;
  all.tick = tick_;
  all.sim_time = engine_->sim_time();
  all.robots = ToRobotPositions(engine_->TakeTruth());
  positions_pub_.publish(all);
  missions_->PublishObjects(tick_);
}

void Simulator::PublishPoses() {
  if (!params_.pose_topics) return;  // no robot_<id>/pose (host_sim's default)
  for (const auto& entry : *links_) {
    if (entry.second.pose_subscribers == 0) continue;
    const sim::Robot* robot = world_->Find(entry.first);
    if (robot != nullptr) entry.second.pose.publish(ToPoseMsg(robot->pose, robot->last_velocity));
  }
}

void Simulator::PublishVisualsIfDue() {
  if (visuals_->Due()) visuals_->Publish(*world_, missions_->missions(), Stamp(), tick_);
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
    if (hold_->holding()) s->message += " (held: ~hold)";
    s->Add("tick", tick_);
    s->Add("sim_time_s", SimTime());
    s->Add("robots", static_cast<std::uint64_t>(robots));
    s->Add("answering", static_cast<std::uint64_t>(live));
    s->Add("missions", static_cast<std::uint64_t>(missions_->missions().size()));
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
  if (std::this_thread::get_id() != thread_) return direct_commands_.Post(id, command);
  OnCmdVel(id, command);
}

void Simulator::SendAnswer(std::uint16_t id, const Tick_Answer& answer) {
  OnSimulatorThread([this, id, answer]() { OnAnswer(id, ToAnswer(answer)); });
}

void Simulator::OnAnswer(std::uint16_t id, const core::Answer& answer) {
  if (finished_ || links_->Find(id) == nullptr) return;
  session_->OnAnswer(id, answer, tick_);
}

void Simulator::OnCmdVel(std::uint16_t id, const geometry_msgs::Twist& msg) {
  if (links_->Find(id) == nullptr || finished_) return;
  const bool finite = IsFinite(msg);
  if (!finite && bad_cmd_warning_.Due()) {
    ROS_WARN("simulator: robot %u sent a cmd_vel with a non-finite value; it stands instead", id);
  }
  if (lockstep_ && session_->Live(id)) {
    // A lock-step robot's command comes in its answer; a cmd_vel beside it would race it.
    if (unsolicited_warning_.Due()) {
      ROS_WARN("lockstep: ignored a cmd_vel for robot %u, which answers its ticks (tick %llu)", id,
               static_cast<unsigned long long>(tick_));
    }
    return;
  }
  // Real time, or a robot outside the lock-step protocol: the command applies at once.
  if (finite) world_->SetCommand(id, ToVelocity(msg), nullptr);
}

void Simulator::ApplyRecruitStatists() {
  std::set<std::pair<std::uint16_t, std::uint8_t>> standing;
  for (const Robot_Position& statist : session_->RecruitStatists(tick_)) {
    const auto key = std::make_pair(statist.robot_id, statist.sub_id);
    standing.insert(key);
    if (recruit_statists_.count(key) == 0) roster_->relayed().Take(ToPosition(statist));
  }
  for (const auto& key : recruit_statists_) {
    if (standing.count(key) == 0) roster_->relayed().Erase(key.first, key.second);
  }
  recruit_statists_ = std::move(standing);
}

}  // namespace swarm_transport
