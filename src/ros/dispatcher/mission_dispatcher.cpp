#include "swarm_transport/ros/dispatcher/mission_dispatcher.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "swarm_transport/Delete_Object.h"
#include "swarm_transport/Delete_Robot.h"
#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/Mission_Schedule.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/graph.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

using core::MissionPhase;

constexpr char kNode[] = "mission_dispatcher";
// Before publishing a new order, wait at most this long (wall) for every node the master lists
// as a subscriber of the order and status topics to be connected.
constexpr double kListenerWaitS = 1.0;
constexpr std::uint32_t kOrderQueue = 256;
constexpr double kSilentWallGraceS = 1.0;
constexpr double kListenerPollS = 0.005;
// At most this many missions recruit at once: each has a statist of its own (ids 65535 down).
constexpr std::size_t kMaxRecruiting = 256;
// A recruit's statist counts this many times in every centroid (stacked copies, thesis 5.5.3):
// one would weigh as little as one robot of a neighbourhood (statist_pull uses 3 as well).
constexpr int kRecruitStatistCopies = 3;

const char* EventName(core::MissionEventKind kind) {
  return kind == core::MissionEventKind::kLoaded ? "LOADED" : "UNLOADED";
}

}  // namespace

MissionDispatcher::MissionDispatcher(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh) {}

bool MissionDispatcher::LoadOptions(std::string* error) {
  if (!ReadDispatcherOptions(nh_, private_nh_, &config_, &options_, &file_missions_, error,
                             &file_ticks_)) {
    return false;
  }
  book_ = std::make_unique<core::MissionBook>(MissionBookParamsOf(config_, options_));
  return true;
}

bool MissionDispatcher::Initialize() {
  std::string error;
  if (!LoadOptions(&error)) {
    ROS_FATAL("%s: invalid parameters: %s", kNode, error.c_str());
    return false;
  }
  // Latched so that a robot (or `rostopic echo`) connecting later still gets the last order.
  // Its queue holds a whole table of live orders published at once (a flood's admitted ones).
  new_pub_ = nh_.advertise<New_Mission>(names::kMissionNew, kOrderQueue, true);
  status_pub_ = nh_.advertise<Mission_Status>(names::kMissionStatus, 100);
  event_pub_ = nh_.advertise<Mission_Event>(names::kMissionEvent, 10);
  delete_pub_ = nh_.advertise<Delete_Object>(names::kObjectDelete, 10);
  lockstep_ = ros::Time::isSimTime();
  // Lock-step: published again at every tick a mission recruits (SPEC 9.4); none may be lost.
  if (lockstep_) {
    schedule_pub_ = nh_.advertise<Mission_Schedule>(names::kMissionSchedule, 100, true);
  } else {
    statist_pub_ = nh_.advertise<Robot_Position>(names::kPosition, 10);
    statist_delete_pub_ = nh_.advertise<Delete_Robot>(names::kRobotDelete, 10);
  }
  positions_sub_ = nh_.subscribe(names::kPositions, 1, &MissionDispatcher::OnPositions, this);
  new_sub_ = nh_.subscribe(names::kMissionNew, 100, &MissionDispatcher::OnNewMission, this);
  status_sub_ = nh_.subscribe(names::kMissionStatus, 100, &MissionDispatcher::OnStatus, this);
  progress_sub_ = nh_.subscribe(names::kMissionProgress, 100, &MissionDispatcher::OnProgress, this);
  // Private names: with the default node name they are names::kSubmitMission and
  // names::kSignalMission.
  submit_srv_ = private_nh_.advertiseService("submit", &MissionDispatcher::OnSubmit, this);
  signal_srv_ = private_nh_.advertiseService("signal", &MissionDispatcher::OnSignal, this);
  status_srv_ = private_nh_.advertiseService("status", &MissionDispatcher::OnStatusService, this);
  diagnostics_ = std::make_unique<NodeDiagnostics>(nh_, "swarm_transport: mission_dispatcher");
  status_timer_ = nh_.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) {
    diagnostics_->PublishIfDue([this](NodeStatus* s) {
      const int live = book_->LiveCount();
      s->message = std::to_string(live) + " live mission(s)";
      s->Add("live_missions", static_cast<std::uint64_t>(live));
      s->Add("missions_known", static_cast<std::uint64_t>(book_->entries().size()));
      s->Add("max_live_missions", static_cast<std::uint64_t>(options_.max_live_missions));
    });
  });
  if (options_.silent_abort_ticks > 0) {
    // On ros::Time (simulated in lock-step), ten times per silence limit.
    watchdog_timer_ =
        nh_.createTimer(ros::Duration(options_.silent_abort_ticks * config_.tick_period_s / 10.0),
                        &MissionDispatcher::OnWatchdog, this);
  }

  const auto delay = [](double s) {
    std::ostringstream os;
    if (s < 0.0) {
      os << "on a signal only";
    } else {
      os << "after " << s << " s";
    }
    return os.str();
  };
  ROS_INFO("%s: up (arena %.3f m, LOADED %s, UNLOADED %s, %zu file mission(s), at most %d live)",
           kNode, config_.flocking.world_size_m, delay(options_.loaded_delay_s).c_str(),
           delay(options_.unloaded_delay_s).c_str(), file_missions_.size(),
           options_.max_live_missions);
  if (!file_missions_.empty()) {
    ROS_INFO("%s: submitting the file missions %.2f s after the first %s%s", kNode,
             options_.start_delay_s, names::kPositions,
             lockstep_ ? " (lock-step: stamped with that tick, sent at once)" : "");
  }
  return true;
}

void MissionDispatcher::Shutdown() {
  for (ros::Timer& timer : start_timers_) timer.stop();
  watchdog_timer_.stop();
  status_timer_.stop();
}

bool MissionDispatcher::FromSelf(const std::string& publisher) const {
  return publisher == ros::this_node::getName();
}

std::set<std::uint16_t> MissionDispatcher::KnownRobots() const {
  std::set<std::uint16_t> known;
  if (positions_) {
    for (const Robot_Position& r : positions_->robots) {
      if (r.type == Robot_Position::TYPE_PHYSICAL) known.insert(r.robot_id);
    }
  }
  return known;
}

std::map<std::uint16_t, core::PlannerRobot> MissionDispatcher::IdleRobots() const {
  std::set<std::uint16_t> busy;
  for (const auto& kv : book_->entries()) {
    if (kv.second.Live() && kv.second.has_spec) {
      for (std::uint16_t id : kv.second.spec.Assigned()) busy.insert(id);
    }
  }
  std::map<std::uint16_t, core::PlannerRobot> idle;
  if (positions_) {
    for (const Robot_Position& r : positions_->robots) {
      if (r.type != Robot_Position::TYPE_PHYSICAL || busy.count(r.robot_id) > 0) continue;
      idle[r.robot_id] = {{r.pos_x, r.pos_y}, core::Angle(r.angle)};
    }
  }
  return idle;
}

void MissionDispatcher::PublishStatus(const core::MissionSpec& spec, MissionPhase phase,
                                      const std::string& reason, std::uint64_t tick) {
  Mission_Status msg;
  msg.mission_id = spec.id;
  msg.state = static_cast<std::uint8_t>(phase);
  msg.reason = reason;
  msg.stamp = ros::Time::now();
  msg.tick = tick;
  msg.robots_assigned =
      static_cast<std::uint16_t>(std::min<std::size_t>(spec.Assigned().size(), 65535));
  if (spec.all_finite && !spec.LeaderOnly()) {
    msg.object_position_x = static_cast<float>(spec.object_centre.x);
    msg.object_position_y = static_cast<float>(spec.object_centre.y);
    msg.distance_to_target = static_cast<float>(core::Distance(spec.object_centre, spec.target));
  }
  status_pub_.publish(msg);
}

core::MissionBook::Verdict MissionDispatcher::Submit(core::MissionSpec spec,
                                                     const std::string& source, bool auto_id,
                                                     bool publish, std::uint64_t start_tick) {
  return Submit(std::move(spec), source, auto_id, publish, start_tick, KnownRobots());
}

core::MissionBook::Verdict MissionDispatcher::Submit(core::MissionSpec spec,
                                                     const std::string& source, bool auto_id,
                                                     bool publish, std::uint64_t start_tick,
                                                     const std::set<std::uint16_t>& robots) {
  if (spec.recruit) return StartRecruit(std::move(spec), source, auto_id, start_tick);
  if (spec.robot_count > 0 && spec.robot_ids.empty() && spec.range_from >= spec.range_to) {
    // A count-only order: the robots are picked by the selection matrix (SPEC 9.10); the order
    // goes out with their ids. Nothing is picked from a swarm the dispatcher has not heard yet.
    core::SelectionParams planner;
    planner.speed_m = config_.flocking.speed_m_per_tick;
    planner.turn_deg = config_.transport.planner_turn_deg_per_tick;
    planner.corridor_m = config_.flocking.MinSeparation();
    const std::string why = core::PickRobotsByCount(&spec, IdleRobots(), planner);
    if (!why.empty()) {
      core::MissionBook::Verdict refused;
      refused.id = spec.id;
      refused.reason = why;
      refused.message = "mission " + std::to_string(spec.id) + " rejected: " + why;
      refused.spec = spec;
      ROS_WARN("%s: rejected mission %u from %s: %s", kNode, refused.id, source.c_str(),
               why.c_str());
      PublishStatus(refused.spec, MissionPhase::kRejected, why);
      return refused;
    }
    ROS_INFO("%s: mission %u from %s: robot_count picked robots %s", kNode, spec.id, source.c_str(),
             core::DescribeMission(spec).c_str());
  }
  const core::MissionBook::Verdict verdict =
      book_->Submit(std::move(spec), source, auto_id, !publish, robots, ros::Time::now().toSec());
  if (!verdict.accepted) {
    ROS_WARN("%s: rejected mission %u from %s: %s", kNode, verdict.id, source.c_str(),
             verdict.reason.c_str());
    PublishStatus(verdict.spec, MissionPhase::kRejected, verdict.reason);
    return verdict;
  }
  if (verdict.attached) {
    ROS_INFO("%s: mission %u from %s: its first leader had reported it already", kNode, verdict.id,
             source.c_str());
    return verdict;
  }
  // No QUEUED status from here: the mission's first leader reports it when it holds the order,
  // and every later phase too, so that a subscriber gets them in order over one connection (a
  // QUEUED of the dispatcher's raced the first leader's GATHERING, issue 9).
  if (publish) {
    AwaitListeners();
    New_Mission order = ToNewMission(verdict.spec);
    order.start_tick = start_tick;
    new_pub_.publish(order);
  }
  ROS_INFO("%s: queued mission %u from %s: %s", kNode, verdict.id, source.c_str(),
           core::DescribeMission(verdict.spec).c_str());
  return verdict;
}

core::MissionBook::Verdict MissionDispatcher::StartRecruit(core::MissionSpec spec,
                                                           const std::string& source, bool auto_id,
                                                           std::uint64_t start_tick) {
  if (auto_id && spec.id == 0) {
    do {
      spec.id = book_->NextFreeId();
    } while (recruiting_.count(spec.id) > 0);
  }
  std::map<std::uint16_t, core::PlannerRobot> idle_robots = IdleRobots();
  std::set<std::uint16_t> idle;
  for (const auto& kv : idle_robots) idle.insert(kv.first);
  core::MissionContext context = book_->Context(KnownRobots());
  for (const auto& kv : recruiting_) context.live_missions.insert(kv.first);
  std::string why = core::ValidateRecruit(spec, idle, context);
  if (why.empty() && recruiting_.size() >= kMaxRecruiting) {
    why = "already " + std::to_string(kMaxRecruiting) + " missions recruit";
  }
  if (why.empty() &&
      book_->LiveCount() + static_cast<int>(recruiting_.size()) >= options_.max_live_missions) {
    why = "already " + std::to_string(options_.max_live_missions) + " live missions";
  }
  core::MissionBook::Verdict verdict;
  verdict.id = spec.id;
  verdict.spec = spec;
  if (!why.empty()) {
    verdict.reason = why;
    verdict.message = "mission " + std::to_string(spec.id) + " rejected: " + why;
    ROS_WARN("%s: rejected mission %u from %s: %s", kNode, spec.id, source.c_str(), why.c_str());
    PublishStatus(spec, MissionPhase::kRejected, why);
    return verdict;
  }
  std::set<std::uint16_t> statists_used;
  for (const auto& kv : recruiting_) statists_used.insert(kv.second.statist_id);
  std::uint16_t statist_id = Mission_Schedule::RECRUIT_STATIST_ID;
  while (statists_used.count(statist_id) > 0) --statist_id;
  Recruiting r{spec, core::RecruitWatch(spec), source, 0, statist_id};
  const std::uint64_t now_tick = positions_ ? positions_->tick : 0;
  r.start_tick = start_tick > now_tick ? start_tick : now_tick + 1;
  recruiting_.emplace(spec.id, r);
  verdict.accepted = true;
  verdict.message = "mission " + std::to_string(spec.id) + " recruiting: a statist at (" +
                    std::to_string(spec.object_centre.x) + ", " +
                    std::to_string(spec.object_centre.y) + ") gathers " +
                    std::to_string(spec.robot_count) + " robots";
  if (lockstep_) {
    // The simulator places the statist from the schedule at its start tick (the file missions'
    // schedule carries it at the first positions).
    if (file_missions_scheduled_) PublishRecruitSchedule(now_tick, {});
  } else {
    Robot_Position statist;
    statist.robot_id = statist_id;
    statist.type = Robot_Position::TYPE_STATIST;
    statist.pos_x = static_cast<float>(spec.object_centre.x);
    statist.pos_y = static_cast<float>(spec.object_centre.y);
    for (int copy = 0; copy < kRecruitStatistCopies; ++copy) {
      statist.sub_id = static_cast<std::uint8_t>(copy);
      statist_pub_.publish(statist);
    }
  }
  ROS_INFO("%s: mission %u from %s recruits %u robots with a statist at (%.3f, %.3f)%s", kNode,
           spec.id, source.c_str(), spec.robot_count, spec.object_centre.x, spec.object_centre.y,
           lockstep_ ? (" from tick " + std::to_string(r.start_tick)).c_str() : "");
  return verdict;
}

void MissionDispatcher::PublishRecruitSchedule(
    std::uint64_t checked_tick, const std::vector<std::pair<std::uint16_t, std::uint64_t>>& due) {
  Mission_Schedule schedule;
  for (const auto& order : due) {
    schedule.mission_ids.push_back(order.first);
    schedule.start_ticks.push_back(order.second);
  }
  schedule.checked_tick = checked_tick;
  for (const auto& kv : recruiting_) {
    schedule.recruiting.push_back(kv.first);
    schedule.recruit_start_ticks.push_back(kv.second.start_tick);
    schedule.statist_x.push_back(static_cast<float>(kv.second.spec.object_centre.x));
    schedule.statist_y.push_back(static_cast<float>(kv.second.spec.object_centre.y));
    schedule.statist_ids.push_back(kv.second.statist_id);
    schedule.statist_copies.push_back(kRecruitStatistCopies);
  }
  schedule_pub_.publish(schedule);
}

void MissionDispatcher::WatchRecruits(const Robot_Positions& positions) {
  if (recruiting_.empty()) return;
  std::map<std::uint16_t, core::Vec2> idle;
  for (const auto& kv : IdleRobots()) idle[kv.first] = kv.second.position;
  std::vector<std::pair<std::uint16_t, std::uint64_t>> due;
  for (auto it = recruiting_.begin(); it != recruiting_.end();) {
    Recruiting& r = it->second;
    // Lock-step: its statist stands from its start tick; the robots before it are not watched.
    if ((lockstep_ && positions.tick < r.start_tick) || !r.watch.Observe(idle)) {
      ++it;
      continue;
    }
    const std::vector<std::uint16_t> recruits = r.watch.Recruits();
    for (std::uint16_t id : recruits) idle.erase(id);  // not for another recruit of this tick
    core::MissionSpec order = core::RecruitedOrder(r.spec, recruits);
    std::ostringstream first;
    for (std::size_t i = 0; i < recruits.size(); ++i) first << (i ? "," : "") << recruits[i];
    ROS_INFO(
        "%s: mission %u: %zu robots inside its object at tick %llu (first in: %s); its "
        "statist is deleted",
        kNode, order.id, recruits.size(), static_cast<unsigned long long>(positions.tick),
        first.str().c_str());
    if (!lockstep_) {
      Delete_Robot gone;
      gone.robot_id = r.statist_id;
      for (int copy = 0; copy < kRecruitStatistCopies; ++copy) {
        gone.sub_id = static_cast<std::uint8_t>(copy);
        statist_delete_pub_.publish(gone);
      }
    }
    const std::string source = r.source;
    it = recruiting_.erase(it);
    // The robots take the order at the next tick (lock-step), entering GATHERING inside the
    // object; they freeze for LOADING as in every mission.
    const std::uint64_t start = lockstep_ ? positions.tick + 1 : 0;
    const core::MissionBook::Verdict verdict = Submit(order, source, false, true, start);
    if (verdict.accepted && lockstep_) due.emplace_back(verdict.id, start);
  }
  if (lockstep_) PublishRecruitSchedule(positions.tick, due);
}

void MissionDispatcher::SubmitFileMissions(std::uint64_t at_tick) {
  for (std::size_t i = 0; i < file_missions_.size(); ++i) {
    if (file_ticks_[i] == at_tick) Submit(file_missions_[i], "missions_file", true, true);
  }
}

void MissionDispatcher::ScheduleFileMissions(std::uint64_t tick) {
  // The tick of start_delay_s from the run's start, and never one that has begun.
  const auto delay_ticks =
      static_cast<std::uint64_t>(std::ceil(options_.start_delay_s / config_.tick_period_s - 1e-9));
  Mission_Schedule schedule;
  for (std::size_t i = 0; i < file_missions_.size(); ++i) {
    // A mission's own at_tick, else start_delay_s; never a tick that has begun.
    const std::uint64_t start =
        std::max<std::uint64_t>(tick + 1, file_ticks_[i] > 0 ? file_ticks_[i] : delay_ticks);
    // Checked against the robots of its start tick: those of now, with the spawns and kills
    // of the simulator's events until then (a scenario's robot that joins later can be named).
    const core::MissionBook::Verdict verdict =
        Submit(file_missions_[i], "missions_file", true, true, start,
               RobotsAt(KnownRobots(), options_.events, start));
    if (!verdict.accepted || recruiting_.count(verdict.id) > 0) continue;  // a recruit: below
    schedule.mission_ids.push_back(verdict.id);
    schedule.start_ticks.push_back(start);
    ROS_INFO("%s: file mission %u enters the run at tick %llu", kNode, verdict.id,
             static_cast<unsigned long long>(start));
  }
  file_missions_.clear();
  // With the recruiting file missions and their statists (SPEC 9.4).
  std::vector<std::pair<std::uint16_t, std::uint64_t>> due;
  for (std::size_t i = 0; i < schedule.mission_ids.size(); ++i) {
    due.emplace_back(schedule.mission_ids[i], schedule.start_ticks[i]);
  }
  PublishRecruitSchedule(tick, due);
}

void MissionDispatcher::OnPositions(const Robot_Positions::ConstPtr& msg) {
  positions_ = msg;
  if (lockstep_) {
    // Even without a file: a lock-step simulator holds tick 1 for the schedule.
    if (!file_missions_scheduled_) {
      ScheduleFileMissions(msg->tick);
      file_missions_scheduled_ = true;
    }
    WatchRecruits(*msg);
    return;
  }
  WatchRecruits(*msg);
  if (file_missions_scheduled_ || file_missions_.empty()) return;
  file_missions_scheduled_ = true;
  // Each group of file missions after its at_tick's worth of time (0: start_delay_s).
  for (const std::uint64_t at_tick :
       std::set<std::uint64_t>(file_ticks_.begin(), file_ticks_.end())) {
    const double delay_s =
        at_tick > 0 ? static_cast<double>(at_tick) * config_.tick_period_s : options_.start_delay_s;
    if (delay_s <= 0.0) {
      SubmitFileMissions(at_tick);
      continue;
    }
    // ros::Timer runs on ros::Time: simulated under /use_sim_time, like the robots' ticks.
    start_timers_.push_back(nh_.createTimer(
        ros::Duration(delay_s),
        [this, at_tick](const ros::TimerEvent&) { SubmitFileMissions(at_tick); }, true));
  }
}

void MissionDispatcher::OnWatchdog(const ros::TimerEvent& /*event*/) {
  const double now_s = ros::Time::now().toSec();
  const ros::WallTime now_wall = ros::WallTime::now();
  std::map<std::uint16_t, ros::WallTime> still_silent;
  for (const auto& silent : book_->Silent(now_s)) {
    const std::uint16_t id = silent.first;
    // Silent in sim time may only mean that its status waits in this node's queue: a fast
    // lock-step (10,000 ticks/s in one process) passes 300 ticks in 30 ms of wall time. A
    // mission is ended only when it is still silent after kSilentWallGraceS of wall time.
    const auto seen = silent_since_.find(id);
    const ros::WallTime since = seen == silent_since_.end() ? now_wall : seen->second;
    still_silent[id] = since;
    if ((now_wall - since).toSec() < kSilentWallGraceS) continue;
    const core::MissionSpec spec = book_->Find(id)->spec;
    if (!book_->Abort(id, silent.second, now_s)) continue;
    ROS_WARN("%s: mission %u ABORTED: %s", kNode, id, silent.second.c_str());
    PublishStatus(spec, MissionPhase::kAborted, silent.second, positions_ ? positions_->tick : 0);
    // Its robots drop the mission and its object (and those frozen for it move again).
    Delete_Object msg;
    msg.mission_id = id;
    delete_pub_.publish(msg);
    still_silent.erase(id);
  }
  silent_since_ = std::move(still_silent);
}

void MissionDispatcher::OnNewMission(const ros::MessageEvent<New_Mission const>& event) {
  // The dispatcher hears its own publications on this topic; those are tracked already.
  if (FromSelf(event.getPublisherName())) return;
  // With admission by the dispatcher the robots take only what it publishes: an order it
  // admits from the topic it publishes itself (one decision for dispatcher and robots).
  const bool admit = config_.admission == core::Admission::kDispatcher;
  Submit(ToMissionSpec(*event.getMessage()), "topic (" + event.getPublisherName() + ")", false,
         admit, event.getMessage()->start_tick);
}

bool MissionDispatcher::MayReport(const char* kind, std::uint16_t mission_id,
                                  const std::string& publisher) {
  const core::MissionBook::Entry* entry = book_->Find(mission_id);
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
  if (!MayReport("Mission_Status", msg.mission_id, event.getPublisherName())) return;
  if (msg.state >= core::kPhaseCount) {
    ROS_WARN("%s: ignored a Mission_Status of mission %u from %s: unknown state %u", kNode,
             msg.mission_id, event.getPublisherName().c_str(), msg.state);
    return;
  }
  if (!std::isfinite(msg.object_position_x) || !std::isfinite(msg.object_position_y) ||
      !std::isfinite(msg.distance_to_target)) {
    ROS_WARN("%s: ignored a Mission_Status of mission %u from %s: a field is not finite", kNode,
             msg.mission_id, event.getPublisherName().c_str());
    return;
  }
  core::MissionReport report = ToMissionReport(msg);
  const core::MissionBook::StatusOutcome outcome =
      book_->OnStatus(report, ros::Time::now().toSec());
  if (outcome.ignored == "too many live missions" && untracked_warning_.Due()) {
    ROS_WARN("%s: not tracking mission %u: too many live missions%s", kNode, msg.mission_id,
             untracked_warning_.AndMore("missions").c_str());
  }
  if (outcome.followed) {
    ROS_INFO("%s: following mission %u first seen in a status from %s", kNode, msg.mission_id,
             event.getPublisherName().c_str());
  }
  if (outcome.entered) {
    const core::MissionBook::Entry& m = *book_->Find(msg.mission_id);
    ROS_INFO("%s: mission %u is %s%s%s", kNode, msg.mission_id, core::PhaseName(m.phase),
             m.reason.empty() ? "" : ": ", m.reason.c_str());
  }
  for (const core::DueSignal& due : outcome.signals) {
    SendEvent(due.mission_id, due.kind, due.not_before_tick, "with the configured delay");
  }
}

void MissionDispatcher::OnProgress(const ros::MessageEvent<Mission_Status const>& event) {
  const Mission_Status::ConstPtr& msg = event.getMessage();
  if (!MayReport("progress", msg->mission_id, event.getPublisherName())) return;
  if (!std::isfinite(msg->distance_to_target)) return;
  book_->OnProgress(ToMissionReport(*msg), ros::Time::now().toSec());
}

void MissionDispatcher::SendEvent(std::uint16_t id, core::MissionEventKind kind,
                                  std::uint64_t not_before_tick, const char* why) {
  event_pub_.publish(ToEventMsg(core::DueSignal{id, kind, not_before_tick}));
  ROS_INFO("%s: sent %s for mission %u (%s; from tick %llu)", kNode, EventName(kind), id, why,
           static_cast<unsigned long long>(not_before_tick));
}

void MissionDispatcher::AwaitListeners() {
  // A node that subscribed but is not connected yet (start-up, a loaded machine) would get
  // the latched order late: a lock-step run would not repeat. Connections are made by roscpp's
  // own thread, so waiting here (briefly, in a service call) lets them complete.
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(kListenerWaitS);
  while (ros::ok()) {
    TopicNodeCounts graph;
    if (!QueryTopicNodeCounts(&graph)) return;
    if (graph.AllConnected(new_pub_)) return;
    if (ros::WallTime::now() >= until) {
      ROS_WARN(
          "%s: not every subscriber of the mission topics is connected after %.1f s; "
          "publishing anyway",
          kNode, kListenerWaitS);
      return;
    }
    ros::WallDuration(kListenerPollS).sleep();
  }
}

bool MissionDispatcher::OnSubmit(Submit_Mission::Request& req, Submit_Mission::Response& res) {
  const core::MissionBook::Verdict verdict =
      Submit(ToMissionSpec(req.mission), "service", true, true);
  res.code = verdict.accepted ? Submit_Mission::Response::OK : Submit_Mission::Response::REJECTED;
  res.message = verdict.message;
  return true;
}

bool MissionDispatcher::OnSignal(Mission_Signal::Request& req, Mission_Signal::Response& res) {
  res.code = Mission_Signal::Response::ERROR;
  const std::string mission = "mission " + std::to_string(req.mission_id);
  if (req.event != static_cast<std::uint8_t>(core::MissionEventKind::kLoaded) &&
      req.event != static_cast<std::uint8_t>(core::MissionEventKind::kUnloaded)) {
    res.message = "event must be 1 (LOADED) or 2 (UNLOADED) but is " + std::to_string(req.event);
  } else {
    res.message = book_->Signal(req.mission_id, static_cast<core::MissionEventKind>(req.event));
  }
  if (!res.message.empty()) {
    ROS_WARN("%s: refused a signal: %s", kNode, res.message.c_str());
    return true;
  }
  const auto kind = static_cast<core::MissionEventKind>(req.event);
  SendEvent(req.mission_id, kind, 0, "requested through ~signal");
  res.code = Mission_Signal::Response::OK;
  res.message = std::string(EventName(kind)) + " sent for " + mission + " (now " +
                core::PhaseName(book_->Find(req.mission_id)->phase) + ")";
  return true;
}

bool MissionDispatcher::OnStatusService(std_srvs::Trigger::Request& /*req*/,
                                        std_srvs::Trigger::Response& res) {
  res.success = true;
  res.message = book_->Table(ros::Time::now().toSec());
  // The tick of the poses it picks robots from (a count-only order): a test that holds the run
  // waits for it instead of sleeping.
  if (positions_) {
    res.message += "positions of tick " + std::to_string(positions_->tick) + "\n";
  }
  return true;
}

}  // namespace swarm_transport
