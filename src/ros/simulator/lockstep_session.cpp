#include "swarm_transport/ros/simulator/lockstep_session.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/graph.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

// Relay sender of a scenario's timed events (sorted before the robots' "robot_NNNNN").
constexpr char kEventsSender[] = "events";

constexpr std::uint32_t kMissionQueue = 100;
// Polling period of the lock-step waits (s): also bounds a robot-less tick to ~1 ms.
constexpr double kPollS = 0.001;
// Period of the start wait (s).
constexpr double kIdleS = 0.01;
// A robot must be connected this long (wall s) before lock-step counts on its answers.
constexpr double kSettleS = 0.2;

}  // namespace

LockstepSession::LockstepSession(ros::NodeHandle nh, const SimulatorParams& params,
                                 RobotLinks* links, ros::CallbackQueue* command_queue,
                                 sim::LockstepEngine* engine, LockstepHooks hooks)
    : nh_(nh),
      params_(params),
      links_(links),
      command_queue_(command_queue),
      engine_(engine),
      hooks_(std::move(hooks)) {}

void LockstepSession::Connect() {
  // The lock-step barrier for mission messages: what arrives during tick k is relayed in every
  // round of tick k + 1 (robots in lock-step do not subscribe to these topics). The relay
  // orders messages by their publishing node (and skips what this node publishes itself).
  relay_topics_.SubscribeFrom(
      nh_,
      [this](const core::MissionMessage& message, const std::string& publisher,
             std::uint64_t start_tick) { Relay(message, publisher, start_tick); },
      kMissionQueue);
  observer_topics_.Advertise(nh_, kMissionQueue);
  if (params_.lockstep_dispatcher) {
    // Its answers (Dispatcher_Answer): tick 1 on waits for the first.
    barrier_.ExpectDispatcher();
    answer_sub_ = nh_.subscribe(names::kDispatcherAnswer, kMissionQueue,
                                &LockstepSession::OnDispatcherAnswer, this);
    ROS_INFO("lockstep: ticks wait for the dispatcher's answers and what they name");
  }
}

void LockstepSession::Inject(const core::MissionMessage& message) {
  engine_->relay().Add(kEventsSender, message);
  observer_topics_.Publish(message);
}

void LockstepSession::Shutdown() {
  relay_topics_.Shutdown();
  answer_sub_.shutdown();
}

void LockstepSession::AddRobot(std::uint16_t id) {
  barrier_.Add(id);
  if (started_) joining_.insert(id);
}

void LockstepSession::RemoveRobot(std::uint16_t id) {
  barrier_.Remove(id);
  joining_.erase(id);
  connected_.erase(id);
}

void LockstepSession::Round(std::size_t index, std::uint16_t id, core::Round* round) {
  const std::size_t standing = engine_->Round(index, connected_.erase(id) > 0, round);
  if (standing > 0 && round->tick > 0) {
    ROS_INFO(
        "lockstep: robot %u connected: its first round (tick %llu) carries the orders of "
        "the %zu mission(s) sent before that have not ended",
        id, static_cast<unsigned long long>(round->tick), standing);
  }
}

void LockstepSession::BeginTick(std::uint64_t tick) {
  WaitForJoining(tick);
  UpdateLiveness(tick);
  // A phase status relayed now makes its dispatcher event due in this tick's relay.
  WaitForDispatcher(tick);
}

void LockstepSession::Finish() {
  finished_ = true;
  barrier_.EndAll();
}

bool LockstepSession::RelaysConnected(const ros::Publisher& robot_list) const {
  TopicNodeCounts graph;
  if (!QueryTopicNodeCounts(&graph)) return false;
  if (!relay_topics_.AllConnected(graph)) return false;
  // Every observer of the robots' mission messages (a recorder, an experiment's runner) hears
  // them from the first tick: not latched, and a short lock-step mission may be over in a
  // fraction of a wall second, before a connection still under way is up.
  if (!observer_topics_.AllConnected(graph)) return false;
  // Every subscriber of the (latched) robot list has it: a robot checks a mission's robots
  // against it, and one without it would accept an order naming a robot that does not exist.
  return graph.AllConnected(robot_list);
}

void LockstepSession::WaitForStart(const ros::Publisher& positions,
                                   const ros::Publisher& robot_list) {
  const ros::WallTime deadline =
      ros::WallTime::now() + ros::WallDuration(params_.lockstep_start_timeout_s);
  std::size_t connected = 0;
  ros::WallTime ready_since;
  while (hooks_.running()) {
    connected = 0;
    for (auto& entry : *links_) {
      if (RobotLinks::Ready(&entry.second, kSettleS)) ++connected;
    }
    const bool observed =
        params_.lockstep_observers == 0 ||
        positions.getNumSubscribers() >= static_cast<std::uint32_t>(params_.lockstep_observers);
    const ros::WallTime now = ros::WallTime::now();
    // Asks the master only once the cheap conditions hold.
    const bool ready = connected == links_->size() && observed && RelaysConnected(robot_list);
    if (ready) {
      // A link counts before its handshake is done (see Ready), and what was published before
      // the last observer subscribed (a latched mission, one sent just before an experiment's
      // runner subscribes) may still be on its way: everything must stay connected a moment,
      // taking it in, so that it is relayed at tick 0 whatever the scheduling.
      if (ready_since.isZero()) ready_since = now;
      hooks_.spin(0.0);
      if ((now - ready_since).toSec() >= kSettleS) break;
      ros::WallDuration(kIdleS).sleep();
      continue;
    }
    ready_since = ros::WallTime();
    if (ros::WallTime::now() >= deadline) {
      ROS_WARN(
          "lockstep: only %zu of %zu robots connected (mission relays %s) after %.1f s; "
          "starting anyway (the others join when they connect)",
          connected, links_->size(),
          RelaysConnected(robot_list) ? "connected" : "not all connected",
          params_.lockstep_start_timeout_s);
      break;
    }
    hooks_.spin(0.0);
    hooks_.visuals();
    ros::WallDuration(kIdleS).sleep();
  }
  ROS_INFO("lockstep: %zu robots connected", connected);
  started_ = true;
}

void LockstepSession::WaitForJoining(std::uint64_t tick) {
  // A robot spawned while a process for its id runs (`robot.launch id:=N` started first idles
  // until the id is listed) is waited for as the robots are at the start, so that it answers
  // from its first tick in the world whatever the scheduling (issue 11: a new robot flocks
  // within a tick of appearing). A robot spawned before its process starts stands until the
  // process connects (UpdateLiveness); directly linked robots answer at once.
  std::vector<std::uint16_t> awaited;
  for (std::uint16_t id : joining_) {
    const RobotLink* link = links_->Find(id);
    if (link != nullptr && !link->direct && link->answer) awaited.push_back(id);
  }
  joining_.clear();
  TopicNodeCounts graph;
  if (awaited.empty() || !QueryTopicNodeCounts(&graph)) return;
  awaited.erase(std::remove_if(awaited.begin(), awaited.end(),
                               [this, &graph](std::uint16_t id) {
                                 return graph.Publishers(links_->Find(id)->answer.getTopic()) == 0;
                               }),
                awaited.end());
  const auto connected = [this, &awaited] {
    for (std::uint16_t id : awaited) {
      RobotLink* link = links_->Find(id);  // a /kill meanwhile removes it
      if (link != nullptr && !RobotLinks::Ready(link, kSettleS)) return false;
    }
    return true;
  };
  const ros::WallTime deadline =
      ros::WallTime::now() + ros::WallDuration(params_.lockstep_start_timeout_s);
  while (!connected() && hooks_.running() && ros::WallTime::now() < deadline) {
    hooks_.spin(kPollS);
  }
  if (!connected() && hooks_.running()) {
    ROS_WARN(
        "lockstep tick %llu: a joining robot's process did not connect within %.1f s; "
        "it stands until it does",
        static_cast<unsigned long long>(tick), params_.lockstep_start_timeout_s);
  }
}

void LockstepSession::UpdateLiveness(std::uint64_t tick) {
  for (auto& entry : *links_) {
    const std::uint16_t id = entry.first;
    RobotLink& link = entry.second;
    const bool live = barrier_.Live(id);
    if (link.silent && !link.Listening()) {
      link.silent = false;  // gone: a process that connects under its id is a fresh start
      link.connected_since = ros::WallTime();
    }
    if (!live && !link.silent && RobotLinks::Ready(&link, kSettleS)) {
      barrier_.MakeLive(id);
      connected_.insert(id);
      if (tick > 0) {
        ROS_INFO("lockstep: robot %u connected at tick %llu", id,
                 static_cast<unsigned long long>(tick));
      }
    } else if (live && !link.Listening()) {
      barrier_.MakeNotLive(id);
      link.connected_since = ros::WallTime();
      ROS_WARN("lockstep: robot %u disconnected at tick %llu", id,
               static_cast<unsigned long long>(tick));
    }
  }
}

void LockstepSession::WaitForAnswers(std::uint64_t tick) {
  const ros::WallTime deadline =
      ros::WallTime::now() + ros::WallDuration(params_.lockstep_timeout_s);
  bool complete = false;
  do {
    // Directly linked robots tick here; their answers are in when this returns.
    hooks_.spin_robots();
    ros::spinOnce();
    complete = barrier_.AllAnswered();
    // Block for answers only while some are missing (with direct robots only: none are).
    command_queue_->callAvailable(ros::WallDuration(complete ? 0.0 : kPollS));
    complete = barrier_.AllAnswered();
    hooks_.visuals();
  } while (!complete && hooks_.running() && ros::WallTime::now() < deadline);
  // Whatever robots sent besides their answers (virtual copies) is in before the next round.
  ros::spinOnce();
  TakeAnswers();
  if (barrier_.AllAnswered() || !hooks_.running()) return;
  const std::vector<std::uint16_t> late = barrier_.Late();
  const std::size_t live = barrier_.LiveCount();
  // Out of the barrier until they answer again: a hung or dead robot must not cost the
  // timeout every tick. They stand; they still are in the world and heard by the others.
  for (std::uint16_t id : late) {
    barrier_.MakeNotLive(id);
    if (RobotLink* link = links_->Find(id)) link->silent = true;
  }
  if (late_warning_.Due()) {
    ROS_WARN(
        "lockstep tick %llu: %zu of %zu robots did not answer within %.2f s (first: robot "
        "%d); they stand and are not waited for until they answer again",
        static_cast<unsigned long long>(tick), late.size(), live, params_.lockstep_timeout_s,
        late.empty() ? -1 : static_cast<int>(late.front()));
  }
}

void LockstepSession::Relay(const core::MissionMessage& message, const std::string& from,
                            std::uint64_t start_tick) {
  // What this node publishes are its robots' answers, relayed by TakeAnswers already.
  if (from == ros::this_node::getName()) return;
  // Robots send their mission messages inside their answers; on the topics only the
  // dispatcher's orders (with admission by the robots anyone's) and its statuses, object deletes
  // and updates count (core::MayOrder, core::MayReport): a hand-made status or object message
  // never reaches the robots.
  const core::Sender sender = SenderOf(from);
  const auto* order = std::get_if<core::MissionSpec>(&message);
  if (order != nullptr && !core::MayOrder(params_.swarm.admission, sender)) return;
  if ((std::holds_alternative<core::PhaseStatus>(message) ||
       std::holds_alternative<core::ObjectUpdate>(message) ||
       std::holds_alternative<core::ObjectDelete>(message)) &&
      sender.kind != core::SenderKind::kDispatcher) {
    if (refused_warning_.Due()) {
      ROS_WARN(
          "lockstep: ignored a mission message of mission %u from %s: only the mission's "
          "robots and the dispatcher may send it",
          core::MissionIdOf(message), from.c_str());
    }
    return;
  }
  if (order != nullptr) {
    engine_->relay().AddOrder(from, *order, start_tick);
    barrier_.OrderArrived(order->id);
  } else {
    engine_->relay().Add(from, message);
  }
  if (const auto* status = std::get_if<core::PhaseStatus>(&message)) {
    NoteStatus(status->mission_id, status->phase);
  }
  if (const auto* signal = std::get_if<core::Signal>(&message)) {
    if (params_.lockstep_dispatcher) {
      barrier_.EventArrived({signal->mission_id, static_cast<std::uint8_t>(signal->kind)});
    }
  }
}

void LockstepSession::NoteStatus(std::uint16_t mission_id, core::MissionPhase phase) {
  if (!params_.lockstep_dispatcher) return;
  // An ended mission's id may be used again.
  if (phase == core::MissionPhase::kDone || phase == core::MissionPhase::kAborted ||
      phase == core::MissionPhase::kRejected) {
    barrier_.Forget(mission_id);
  }
}

void LockstepSession::WaitForDispatcher(std::uint64_t tick) {
  if (!barrier_.DispatcherPending(tick)) return;
  // Its first answer or an order is due once per run and may wait for the dispatcher's
  // listeners: the start-up timeout; the rest the tick timeout.
  const sim::LockstepBarrier::DispatcherWait waiting = barrier_.WaitsFor(tick);
  const double timeout_s = waiting.first || !waiting.orders.empty()
                               ? params_.lockstep_start_timeout_s
                               : params_.lockstep_timeout_s;
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(timeout_s);
  while (barrier_.DispatcherPending(tick) && hooks_.running() && ros::WallTime::now() < deadline) {
    hooks_.spin(kPollS);
  }
  if (!barrier_.DispatcherPending(tick) || !hooks_.running()) return;
  ROS_WARN(
      "lockstep tick %llu: the dispatcher's answers (%s) are incomplete after %.2f s (%s); not "
      "waiting for them any longer",
      static_cast<unsigned long long>(tick), names::kDispatcherAnswer, timeout_s,
      barrier_.GiveUpDispatcher(tick).Text(tick).c_str());
}

void LockstepSession::OnDispatcherAnswer(const Dispatcher_Answer::ConstPtr& msg) {
  core::DispatcherAnswer answer = ToDispatcherAnswer(*msg);
  barrier_.OnDispatcherAnswer(answer);
  // The recruiting missions (SPEC 9.4): the whole list each time, with their statists.
  recruiting_ = std::move(answer.recruiting);
}

std::vector<Robot_Position> LockstepSession::RecruitStatists(std::uint64_t tick) const {
  std::vector<Robot_Position> standing;
  for (const core::RecruitStatist& r : recruiting_) {
    for (int copy = 0; copy < r.copies && r.from_tick <= tick; ++copy) {
      standing.push_back(StatistPosition(r.statist_id, r.at, static_cast<std::uint8_t>(copy)));
    }
  }
  return standing;
}

void LockstepSession::OnAnswer(std::uint16_t id, const core::Answer& answer, std::uint64_t tick) {
  RobotLink* link = links_->Find(id);
  if (finished_ || link == nullptr) return;
  const bool finite = std::isfinite(answer.command.linear) && std::isfinite(answer.command.angular);
  if (!finite && bad_answer_warning_.Due()) {
    ROS_WARN("lockstep: robot %u answered with a non-finite command; it stands instead", id);
  }
  const auto result = barrier_.OnAnswer(id, answer.tick, core::CommandOf(answer));
  switch (result) {
    case sim::LockstepBarrier::Answer::kAnswer:
    case sim::LockstepBarrier::Answer::kStale:
      // A late answer's command is past, but what it says still holds: relayed a tick late.
      answers_.emplace_back(id, answer);
      break;
    case sim::LockstepBarrier::Answer::kOutside:
      if (link->silent) {
        // A robot that let a tick time out answered at last (its late answer): it is waited
        // for again from the next tick on. What it said still holds.
        link->silent = false;
        answers_.emplace_back(id, answer);
        ROS_INFO("lockstep: robot %u answers again (tick %llu, its answer to tick %llu)", id,
                 static_cast<unsigned long long>(tick),
                 static_cast<unsigned long long>(answer.tick));
        break;
      }
      [[fallthrough]];
    case sim::LockstepBarrier::Answer::kUnsolicited:
      if (unsolicited_warning_.Due()) {
        ROS_WARN(
            "lockstep: robot %u answered tick %llu, which it was not asked (tick %llu); "
            "ignored",
            id, static_cast<unsigned long long>(answer.tick),
            static_cast<unsigned long long>(tick));
      }
      break;
  }
}

void LockstepSession::TakeAnswers() {
  // By robot id, then in arrival order (a late answer before the robot's current one).
  engine_->TakeAnswers(&answers_, [this](std::uint16_t, const core::Answer& a) {
    for (const core::MissionMessage& m : a.messages) observer_topics_.Publish(m);
    const ros::Time stamp(a.sim_time);
    for (const core::StatusReport& r : a.statuses) {
      const Mission_Status st = ToStatusMsg(r, a.tick, stamp);
      NoteStatus(st.mission_id, static_cast<core::MissionPhase>(st.state));
      // The dispatcher answers every status it takes: the next tick waits for that answer.
      if (params_.lockstep_dispatcher) {
        barrier_.StatusRelayed({st.mission_id, static_cast<core::MissionPhase>(st.state), st.tick});
      }
      observer_topics_.PublishStatus(st);
    }
    for (const core::StatusReport& r : a.progress)
      observer_topics_.PublishProgress(ToStatusMsg(r, a.tick, stamp));
  });
}

}  // namespace swarm_transport
