#include "swarm_transport/ros/dispatcher/mission_dispatcher.h"

#include <cmath>

#include "swarm_transport/Delete_Object.h"
#include "swarm_transport/Delete_Robot.h"
#include "swarm_transport/Dispatcher_Answer.h"
#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/mission_resend.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

using core::MissionPhase;

constexpr std::uint32_t kStatusQueue = 4096;
constexpr double kSilentWallGraceS = 1.0;

}  // namespace

MissionDispatcher::MissionDispatcher(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh) {}

bool MissionDispatcher::Initialize() {
  std::string error;
  std::vector<core::MissionSpec> file_missions;
  std::vector<std::uint64_t> file_ticks;
  if (!ReadDispatcherOptions(nh_, private_nh_, &config_, &options_, &file_missions, &error,
                             &file_ticks)) {
    ROS_FATAL("%s: invalid parameters: %s", kNode, error.c_str());
    return false;
  }
  lockstep_ = ros::Time::isSimTime();
  core::DispatcherPolicyParams params = DispatcherPolicyParamsOf(config_, options_, lockstep_);
  params.clock = [] { return ros::Time::now().toSec(); };
  core::DispatcherOutlet* outlet = this;
  policy_ = std::make_unique<core::DispatcherPolicy>(std::move(params), outlet);
  policy_->SetFileMissions(std::move(file_missions), std::move(file_ticks));
  orders_ = std::make_unique<OrderPublisher>(
      nh_, lockstep_,
      [this](std::uint16_t id) {
        const core::MissionBook::Entry* entry = policy_->book().Find(id);
        return entry != nullptr && entry->phase == MissionPhase::kQueued;
      },
      kNode,
      [this](const std::set<std::uint16_t>& unreachable) { policy_->SetUnreachable(unreachable); });
  status_pub_ = nh_.advertise<Mission_Status>(names::kMissionStatus, 100);
  event_pub_ = nh_.advertise<Mission_Event>(names::kMissionEvent, 10);
  delete_pub_ = nh_.advertise<Delete_Object>(names::kObjectDelete, 10);
  // Lock-step: an answer at every positions and status it takes; none may be lost.
  if (lockstep_) {
    answer_pub_ = nh_.advertise<Dispatcher_Answer>(names::kDispatcherAnswer, 100, true);
  } else {
    statist_pub_ = nh_.advertise<Robot_Position>(names::kPosition, 10);
    statist_delete_pub_ = nh_.advertise<Delete_Robot>(names::kRobotDelete, 10);
  }
  positions_sub_ = nh_.subscribe(names::kWorldPoses, 1, &MissionDispatcher::OnPositions, this);
  new_sub_ = nh_.subscribe(names::kMissionNew, 100, &MissionDispatcher::OnNewMission, this);
  // It hears its own REJECTED on the topic too: a flood's 500 of them, while a wait for
  // listeners held its callbacks, pushed a first leader's DONE out of a queue of 100 (a 2-minute
  // soak slice: the mission was then aborted as silent in UNLOADING; issue 29).
  status_sub_ =
      nh_.subscribe(names::kMissionStatus, kStatusQueue, &MissionDispatcher::OnStatus, this);
  progress_sub_ = nh_.subscribe(names::kMissionProgress, 100, &MissionDispatcher::OnProgress, this);
  // Private names: with the default node name they are names::kSubmitMission and
  // names::kSignalMission.
  submit_srv_ = private_nh_.advertiseService("submit", &MissionDispatcher::OnSubmit, this);
  signal_srv_ = private_nh_.advertiseService("signal", &MissionDispatcher::OnSignal, this);
  status_srv_ = private_nh_.advertiseService("status", &MissionDispatcher::OnStatusService, this);
  diagnostics_ = std::make_unique<NodeDiagnostics>(nh_, "swarm_transport: mission_dispatcher");
  status_timer_ = nh_.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) {
    diagnostics_->PublishIfDue([this](NodeStatus* s) {
      const int live = policy_->book().LiveCount();
      s->message = std::to_string(live) + " live mission(s)";
      s->Add("live_missions", static_cast<std::uint64_t>(live));
      s->Add("missions_known", static_cast<std::uint64_t>(policy_->book().entries().size()));
      s->Add("max_live_missions", static_cast<std::uint64_t>(options_.max_live_missions));
    });
  });
  if (options_.silent_abort_ticks > 0 || !lockstep_) {
    // On ros::Time (simulated in lock-step), ten times per silence limit; without one, every
    // second in real time, where it also sends a LOADED / UNLOADED a robot may have missed again.
    const double period_s = options_.silent_abort_ticks > 0
                                ? options_.silent_abort_ticks * config_.tick_period_s / 10.0
                                : 1.0;
    watchdog_timer_ = nh_.createTimer(ros::Duration(period_s), [this](const ros::TimerEvent&) {
      policy_->Watchdog(ros::WallTime::now().toSec(), kSilentWallGraceS);
    });
  }

  if (WasStartedBefore(private_nh_)) {
    if (lockstep_) {
      ROS_WARN(
          "%s: restarted in lock-step: its table starts empty and follows each live mission from "
          "its next status only (a dispatcher restart is supported in real time: "
          "docs/reliability.md)",
          kNode);
    } else {
      rebuild_ = std::make_unique<DispatcherRebuild>(nh_, policy_.get(), kNode);
      rebuild_->Run();
    }
  }

  ROS_INFO("%s: up (arena %.3f m, LOADED %s, UNLOADED %s, %zu file mission(s), at most %d live)",
           kNode, config_.flocking.world_size_m, DelayText(options_.loaded_delay_s).c_str(),
           DelayText(options_.unloaded_delay_s).c_str(), policy_->file_mission_count(),
           options_.max_live_missions);
  if (policy_->file_mission_count() > 0) {
    ROS_INFO("%s: submitting the file missions %.2f s after the first %s%s", kNode,
             options_.start_delay_s, names::kWorldPoses,
             lockstep_ ? " (lock-step: stamped with that tick, sent at once)" : "");
  }
  return true;
}

void MissionDispatcher::Shutdown() {
  ForgetInstance(private_nh_);
  if (rebuild_) rebuild_->Stop();
  for (ros::Timer& timer : start_timers_) timer.stop();
  watchdog_timer_.stop();
  status_timer_.stop();
}

void MissionDispatcher::OnPositions(const Robot_Positions::ConstPtr& msg) {
  for (const auto& later : policy_->OnSwarm(msg->tick, SwarmOf(msg->robots))) {
    // ros::Timer runs on ros::Time: simulated under /use_sim_time, like the robots' ticks.
    const std::uint64_t at_tick = later.first;
    start_timers_.push_back(nh_.createTimer(
        ros::Duration(later.second),
        [this, at_tick](const ros::TimerEvent&) { policy_->SubmitFileMissions(at_tick); }, true));
  }
}

void MissionDispatcher::OnNewMission(const ros::MessageEvent<New_Mission const>& event) {
  // The dispatcher hears its own publications on this topic; those are tracked already.
  if (FromSelf(event.getPublisherName())) return;
  // With admission by the dispatcher the robots take only what it publishes: an order it
  // admits from the topic it publishes itself (one decision for dispatcher and robots).
  const bool admit = config_.admission == core::Admission::kDispatcher;
  orders_->RefreshUnreachable();
  policy_->Submit(ToMissionSpec(*event.getMessage()), "topic (" + event.getPublisherName() + ")",
                  false, admit, event.getMessage()->start_tick);
}

bool MissionDispatcher::MayReport(const char* kind, std::uint16_t mission_id,
                                  const std::string& publisher) {
  const core::MissionBook::Entry* entry = policy_->book().Find(mission_id);
  const core::Sender from = SenderOf(publisher);
  if (core::MayReport(entry != nullptr && entry->has_spec ? &entry->spec : nullptr, from)) {
    return true;
  }
  if (foreign_report_warning_.Due()) {
    ROS_WARN("%s: ignored a %s of mission %u from %s: only the mission's robots may send it%s",
             kNode, kind, mission_id, publisher.c_str(),
             foreign_report_warning_.AndMore("such reports").c_str());
  }
  return false;
}

void MissionDispatcher::OnStatus(const ros::MessageEvent<Mission_Status const>& event) {
  if (FromSelf(event.getPublisherName())) return;
  const Mission_Status& msg = *event.getMessage();
  const std::string problem = StatusProblem(msg);
  const bool may = MayReport("Mission_Status", msg.mission_id, event.getPublisherName());
  if (may && !problem.empty()) {
    ROS_WARN("%s: ignored a Mission_Status of mission %u from %s: %s", kNode, msg.mission_id,
             event.getPublisherName().c_str(), problem.c_str());
  }
  if (!may || !problem.empty()) {  // lock-step: answered all the same
    policy_->SkipStatus({msg.mission_id, static_cast<MissionPhase>(msg.state), msg.tick});
    return;
  }
  const core::MissionBook::StatusOutcome outcome =
      policy_->OnStatus(ToMissionReport(msg), event.getPublisherName());
  orders_->ForgetStarted();
  if (outcome.ignored == "too many live missions" && untracked_warning_.Due()) {
    ROS_WARN("%s: not tracking mission %u: too many live missions%s", kNode, msg.mission_id,
             untracked_warning_.AndMore("missions").c_str());
  }
}

void MissionDispatcher::OnProgress(const ros::MessageEvent<Mission_Status const>& event) {
  const Mission_Status::ConstPtr& msg = event.getMessage();
  if (!MayReport("progress", msg->mission_id, event.getPublisherName())) return;
  if (!std::isfinite(msg->distance_to_target)) return;
  if (rebuild_ && policy_->book().Find(msg->mission_id) == nullptr) {
    rebuild_->AskAgain(msg->mission_id);
  }
  policy_->OnProgress(ToMissionReport(*msg));
}

bool MissionDispatcher::OnSubmit(Submit_Mission::Request& req, Submit_Mission::Response& res) {
  orders_->RefreshUnreachable();
  const core::MissionBook::Verdict verdict =
      policy_->Submit(ToMissionSpec(req.mission), "service", true, true);
  res.code = verdict.accepted ? Submit_Mission::Response::OK : Submit_Mission::Response::REJECTED;
  res.message = verdict.message;
  return true;
}

bool MissionDispatcher::OnSignal(Mission_Signal::Request& req, Mission_Signal::Response& res) {
  const auto kind = static_cast<core::MissionEventKind>(req.event);
  res.message = policy_->Signal(req.mission_id, kind);
  if (!res.message.empty()) {
    res.code = Mission_Signal::Response::ERROR;
    return true;
  }
  res.code = Mission_Signal::Response::OK;
  res.message = std::string(SignalName(kind)) + " sent for mission " +
                std::to_string(req.mission_id) + " (now " +
                core::PhaseName(policy_->book().Find(req.mission_id)->phase) + ")";
  return true;
}

bool MissionDispatcher::OnStatusService(std_srvs::Trigger::Request& /*req*/,
                                        std_srvs::Trigger::Response& res) {
  res.success = true;
  res.message = policy_->Table();
  return true;
}

}  // namespace swarm_transport
