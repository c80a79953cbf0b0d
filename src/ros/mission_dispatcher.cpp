#include "swarm_transport/ros/mission_dispatcher.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iomanip>
#include <sstream>

#include "swarm_transport/Delete_Object.h"
#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/Mission_Schedule.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/ros/conversions.h"
#include "swarm_transport/ros/graph.h"
#include "swarm_transport/ros/names.h"

namespace swarm_transport {
namespace {

using core::MissionPhase;
using XmlRpc::XmlRpcValue;

constexpr char kNode[] = "mission_dispatcher";
constexpr std::size_t kPhaseCount = 8;
// Before publishing a new order, wait at most this long (wall) for every node the master lists
// as a subscriber of the order and status topics to be connected.
constexpr double kListenerWaitS = 1.0;
constexpr double kListenerPollS = 0.005;

// XmlRpc gives ints and doubles as different types; `x: 7` in a YAML file means 7.0.
bool AsDouble(XmlRpcValue& v, double* out) {
  if (v.getType() == XmlRpcValue::TypeDouble) {
    *out = static_cast<double>(v);
  } else if (v.getType() == XmlRpcValue::TypeInt) {
    *out = static_cast<int>(v);
  } else {
    return false;
  }
  return std::isfinite(*out);
}

// An integer in [lo, hi] or false.
bool AsInt(XmlRpcValue& v, int lo, int hi, int* out) {
  if (v.getType() != XmlRpcValue::TypeInt) return false;
  *out = static_cast<int>(v);
  return lo <= *out && *out <= hi;
}

// A list of exactly `n` finite numbers.
bool AsNumbers(XmlRpcValue& v, int n, std::vector<double>* out) {
  if (v.getType() != XmlRpcValue::TypeArray || v.size() != n) return false;
  out->assign(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i) {
    if (!AsDouble(v[i], &(*out)[static_cast<std::size_t>(i)])) return false;
  }
  return true;
}

// Reads one missions-file entry; `error` says which key is wrong.
bool MissionFromXmlRpc(XmlRpcValue& e, core::MissionSpec* spec, std::string* error) {
  static const std::set<std::string> kKeys = {"id",      "robots_from", "robots_to", "robot_ids",
                                              "leaders", "object",      "target",    "mode"};
  if (e.getType() != XmlRpcValue::TypeStruct) {
    *error = "must be a dictionary";
    return false;
  }
  for (auto& kv : e) {
    if (kKeys.count(kv.first) == 0) {
      *error = "unknown key '" + kv.first +
               "' (known: id, robots_from, robots_to, robot_ids, leaders, object, target, mode)";
      return false;
    }
  }
  core::MissionSpec m;
  int value = 0;
  if (e.hasMember("id")) {
    if (!AsInt(e["id"], 0, 65535, &value)) {
      *error = "'id' must be an integer in [0, 65535] (0 = next free id)";
      return false;
    }
    m.id = static_cast<std::uint16_t>(value);
  }
  const bool has_range = e.hasMember("robots_from") || e.hasMember("robots_to");
  if (has_range == e.hasMember("robot_ids")) {
    *error = "give either robots_from and robots_to (half-open range) or robot_ids (a list)";
    return false;
  }
  if (has_range) {
    int from = 0, to = 0;
    if (!e.hasMember("robots_from") || !e.hasMember("robots_to") ||
        !AsInt(e["robots_from"], 0, 65535, &from) || !AsInt(e["robots_to"], 0, 65535, &to)) {
      *error = "'robots_from' and 'robots_to' must both be integers in [0, 65535]";
      return false;
    }
    m.range_from = static_cast<std::uint16_t>(from);
    m.range_to = static_cast<std::uint16_t>(to);
  } else {
    XmlRpcValue& ids = e["robot_ids"];
    if (ids.getType() != XmlRpcValue::TypeArray || ids.size() == 0) {
      *error = "'robot_ids' must be a non-empty list of robot ids";
      return false;
    }
    for (int i = 0; i < ids.size(); ++i) {
      if (!AsInt(ids[i], 0, 65535, &value)) {
        *error = "'robot_ids' must hold integers in [0, 65535]";
        return false;
      }
      m.robot_ids.push_back(static_cast<std::uint16_t>(value));
    }
  }
  if (!e.hasMember("leaders") || !AsInt(e["leaders"], 1, 255, &m.leader_number)) {
    *error = "'leaders' must be an integer in [1, 255]";
    return false;
  }
  std::vector<double> v;
  if (!e.hasMember("target") || !AsNumbers(e["target"], 2, &v)) {
    *error = "'target' must be [x, y], finite numbers (m)";
    return false;
  }
  m.target = {v[0], v[1]};
  if (e.hasMember("object")) {
    if (!AsNumbers(e["object"], 4, &v)) {
      *error =
          "'object' must be [x, y, size_x, size_y], finite numbers (m), or left out for a "
          "leader-only mission";
      return false;
    }
    m.object_centre = {v[0], v[1]};
    m.object_size = {v[2], v[3]};
  } else {
    m.object_centre = m.target;  // leader-only: the position is ignored, keep it meaningful
  }
  if (e.hasMember("mode")) {
    XmlRpcValue& mode = e["mode"];
    if (mode.getType() == XmlRpcValue::TypeString) {
      const std::string name = static_cast<std::string>(mode);
      value = name == "swarm" ? 0 : name == "formation" ? 1 : -1;
    } else if (!AsInt(mode, 0, 1, &value)) {
      value = -1;
    }
    if (value < 0) {
      *error = "'mode' must be 0 (swarm) or 1 (formation)";
      return false;
    }
    m.transport_mode = static_cast<std::uint8_t>(value);
  }
  *spec = m;
  return true;
}

const char* EventName(core::MissionEventKind kind) {
  return kind == core::MissionEventKind::kLoaded ? "LOADED" : "UNLOADED";
}

}  // namespace

std::string DispatcherOptions::Validate() const {
  std::ostringstream os;
  if (!std::isfinite(loaded_delay_s) || !std::isfinite(unloaded_delay_s)) {
    os << "loaded_delay_s and unloaded_delay_s must be finite (s; negative = never send)";
  } else if (!(start_delay_s >= 0.0) || !std::isfinite(start_delay_s)) {
    os << "~start_delay_s must be a finite number >= 0 (s) but is " << start_delay_s;
  } else if (max_live_missions < 1 || max_live_missions > 65535) {
    os << "~max_live_missions must be in [1, 65535] but is " << max_live_missions;
  } else if (silent_abort_ticks < 0) {
    os << "~silent_abort_ticks must be >= 0 (ticks; 0: never) but is " << silent_abort_ticks;
  }
  return os.str();
}

bool MissionsFromXmlRpc(XmlRpcValue& file, std::vector<core::MissionSpec>* missions,
                        std::string* error) {
  if (file.getType() != XmlRpcValue::TypeStruct || !file.hasMember("missions") ||
      file["missions"].getType() != XmlRpcValue::TypeArray) {
    *error = "the file must hold a list under the key 'missions'";
    return false;
  }
  XmlRpcValue& list = file["missions"];
  std::vector<core::MissionSpec> out;
  for (int i = 0; i < list.size(); ++i) {
    core::MissionSpec spec;
    std::string why;
    if (!MissionFromXmlRpc(list[i], &spec, &why)) {
      *error = "missions[" + std::to_string(i) + "]: " + why;
      return false;
    }
    out.push_back(spec);
  }
  *missions = out;
  return true;
}

MissionDispatcher::MissionDispatcher(ros::NodeHandle nh, ros::NodeHandle private_nh)
    : nh_(nh), private_nh_(private_nh) {}

bool MissionDispatcher::LoadOptions(std::string* error) {
  XmlRpcValue swarm;
  if (nh_.getParam("/swarm", swarm) && !ConfigFromXmlRpc(swarm, &config_, error)) {
    *error = "/swarm: " + *error;
    return false;
  }
  options_.loaded_delay_s = config_.loaded_delay_s;
  options_.unloaded_delay_s = config_.unloaded_delay_s;
  if (!ReadPrivate(private_nh_, "loaded_delay_s", &options_.loaded_delay_s, error) ||
      !ReadPrivate(private_nh_, "unloaded_delay_s", &options_.unloaded_delay_s, error) ||
      !ReadPrivate(private_nh_, "missions_file", &options_.missions_file, error) ||
      !ReadPrivate(private_nh_, "start_delay_s", &options_.start_delay_s, error) ||
      !ReadPrivate(private_nh_, "max_live_missions", &options_.max_live_missions, error) ||
      !ReadPrivate(private_nh_, "silent_abort_ticks", &options_.silent_abort_ticks, error)) {
    return false;
  }
  *error = options_.Validate();
  if (!error->empty()) return false;
  core::MissionBookParams book;
  book.world_size_m = config_.flocking.world_size_m;
  book.tick_period_s = config_.tick_period_s;
  book.loaded_delay_s = options_.loaded_delay_s;
  book.unloaded_delay_s = options_.unloaded_delay_s;
  book.max_live_missions = options_.max_live_missions;
  book.silent_after_s = options_.silent_abort_ticks > 0
                            ? options_.silent_abort_ticks * config_.tick_period_s
                            : -1.0;
  book_ = std::make_unique<core::MissionBook>(book);
  if (options_.missions_file.empty()) return true;

  const std::string& path = options_.missions_file;
  XmlRpcValue file;
  if (!XmlRpcFromYamlFile(path, &file, error)) {
    *error = "~missions_file: " + *error;  // the reader names the path
    return false;
  }
  if (!MissionsFromXmlRpc(file, &file_missions_, error)) {
    *error = "~missions_file " + path + ": " + *error;
    return false;
  }
  // Check what can be checked before any robot is known; ids of the file must not clash.
  core::MissionContext context;
  context.world_size_m = config_.flocking.world_size_m;
  for (std::size_t i = 0; i < file_missions_.size(); ++i) {
    const core::MissionSpec& m = file_missions_[i];
    std::string reason = core::ValidateMission(m, context);
    if (context.live_missions.count(m.id) > 0) {
      reason = "id " + std::to_string(m.id) + " appears twice in the file";
    }
    if (!reason.empty()) {
      *error = "~missions_file " + path + ": missions[" + std::to_string(i) + "]: " + reason;
      return false;
    }
    if (m.id != 0) context.live_missions.insert(m.id);
  }
  return true;
}

bool MissionDispatcher::Initialize() {
  std::string error;
  if (!LoadOptions(&error)) {
    ROS_FATAL("%s: invalid parameters: %s", kNode, error.c_str());
    return false;
  }
  // Latched so that a robot (or `rostopic echo`) connecting later still gets the last order.
  new_pub_ = nh_.advertise<New_Mission>(names::kMissionNew, 10, true);
  status_pub_ = nh_.advertise<Mission_Status>(names::kMissionStatus, 100);
  event_pub_ = nh_.advertise<Mission_Event>(names::kMissionEvent, 10);
  delete_pub_ = nh_.advertise<Delete_Object>(names::kObjectDelete, 10);
  lockstep_ = ros::Time::isSimTime();
  if (lockstep_) schedule_pub_ = nh_.advertise<Mission_Schedule>(names::kMissionSchedule, 1, true);
  positions_sub_ = nh_.subscribe(names::kPositions, 1, &MissionDispatcher::OnPositions, this);
  new_sub_ = nh_.subscribe(names::kMissionNew, 100, &MissionDispatcher::OnNewMission, this);
  status_sub_ = nh_.subscribe(names::kMissionStatus, 100, &MissionDispatcher::OnStatus, this);
  progress_sub_ = nh_.subscribe(names::kMissionProgress, 100, &MissionDispatcher::OnProgress, this);
  // Private names: with the default node name they are names::kSubmitMission and
  // names::kSignalMission.
  submit_srv_ = private_nh_.advertiseService("submit", &MissionDispatcher::OnSubmit, this);
  signal_srv_ = private_nh_.advertiseService("signal", &MissionDispatcher::OnSignal, this);
  status_srv_ = private_nh_.advertiseService("status", &MissionDispatcher::OnStatusService, this);
  if (options_.silent_abort_ticks > 0) {
    // On ros::Time (simulated in lock-step), ten times per silence limit.
    watchdog_timer_ = nh_.createTimer(
        ros::Duration(options_.silent_abort_ticks * config_.tick_period_s / 10.0),
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
  start_timer_.stop();
  watchdog_timer_.stop();
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
  const core::MissionBook::Verdict verdict =
      book_->Submit(std::move(spec), source, auto_id, !publish, KnownRobots(),
                    ros::Time::now().toSec());
  if (!verdict.accepted) {
    ROS_WARN("%s: rejected mission %u from %s: %s", kNode, verdict.id, source.c_str(),
             verdict.reason.c_str());
    PublishStatus(verdict.spec, MissionPhase::kRejected, verdict.reason);
    return verdict;
  }
  if (verdict.attached) {
    ROS_INFO("%s: mission %u from %s: its first leader had reported it already", kNode,
             verdict.id, source.c_str());
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

void MissionDispatcher::SubmitFileMissions() {
  for (const core::MissionSpec& spec : file_missions_) {
    Submit(spec, "missions_file", true, true);
  }
  file_missions_.clear();
}

void MissionDispatcher::ScheduleFileMissions(std::uint64_t tick) {
  // The tick of start_delay_s from the run's start, and never one that has begun.
  const auto delay_ticks = static_cast<std::uint64_t>(
      std::ceil(options_.start_delay_s / config_.tick_period_s - 1e-9));
  const std::uint64_t start = std::max<std::uint64_t>(tick + 1, delay_ticks);
  Mission_Schedule schedule;
  for (const core::MissionSpec& spec : file_missions_) {
    const core::MissionBook::Verdict verdict = Submit(spec, "missions_file", true, true, start);
    if (!verdict.accepted) continue;
    schedule.mission_ids.push_back(verdict.id);
    schedule.start_ticks.push_back(start);
  }
  file_missions_.clear();
  schedule_pub_.publish(schedule);
  if (!schedule.mission_ids.empty()) {
    ROS_INFO("%s: %zu file mission(s) enter the run at tick %llu", kNode,
             schedule.mission_ids.size(), static_cast<unsigned long long>(start));
  }
}

void MissionDispatcher::OnPositions(const Robot_Positions::ConstPtr& msg) {
  positions_ = msg;
  if (lockstep_) {
    // Even without a file: a lock-step simulator holds tick 1 for the schedule.
    if (!file_missions_scheduled_) {
      file_missions_scheduled_ = true;
      ScheduleFileMissions(msg->tick);
    }
    return;
  }
  if (file_missions_scheduled_ || file_missions_.empty()) return;
  file_missions_scheduled_ = true;
  if (options_.start_delay_s > 0.0) {
    // ros::Timer runs on ros::Time: simulated under /use_sim_time, like the robots' ticks.
    start_timer_ = nh_.createTimer(ros::Duration(options_.start_delay_s),
                                   &MissionDispatcher::OnStartTimer, this, true);
  } else {
    SubmitFileMissions();
  }
}

void MissionDispatcher::OnStartTimer(const ros::TimerEvent& /*event*/) { SubmitFileMissions(); }

void MissionDispatcher::OnWatchdog(const ros::TimerEvent& /*event*/) {
  const double now_s = ros::Time::now().toSec();
  for (const auto& silent : book_->Silent(now_s)) {
    const std::uint16_t id = silent.first;
    const core::MissionSpec spec = book_->Find(id)->spec;
    if (!book_->Abort(id, silent.second, now_s)) continue;
    ROS_WARN("%s: mission %u ABORTED: %s", kNode, id, silent.second.c_str());
    PublishStatus(spec, MissionPhase::kAborted, silent.second, positions_ ? positions_->tick : 0);
    // Its robots drop the mission and its object (and those frozen for it move again).
    Delete_Object msg;
    msg.mission_id = id;
    delete_pub_.publish(msg);
  }
}

void MissionDispatcher::OnNewMission(const ros::MessageEvent<New_Mission const>& event) {
  // The dispatcher hears its own publications on this topic; those are tracked already.
  if (FromSelf(event.getPublisherName())) return;
  Submit(ToMissionSpec(*event.getMessage()), "topic (" + event.getPublisherName() + ")", false,
         false);
}

void MissionDispatcher::OnStatus(const ros::MessageEvent<Mission_Status const>& event) {
  if (FromSelf(event.getPublisherName())) return;
  const Mission_Status& msg = *event.getMessage();
  if (msg.state >= kPhaseCount) {
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
  if (outcome.ignored == "too many live missions") {
    ROS_WARN_THROTTLE(5.0, "%s: not tracking mission %u: too many live missions", kNode,
                      msg.mission_id);
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

void MissionDispatcher::OnProgress(const Mission_Status::ConstPtr& msg) {
  if (!std::isfinite(msg->distance_to_target)) return;
  book_->OnProgress(ToMissionReport(*msg), ros::Time::now().toSec());
}

void MissionDispatcher::SendEvent(std::uint16_t id, core::MissionEventKind kind,
                                  std::uint64_t not_before_tick, const char* why) {
  Mission_Event msg;
  msg.mission_id = id;
  msg.event = static_cast<std::uint8_t>(kind);
  msg.not_before_tick = not_before_tick;
  event_pub_.publish(msg);
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
  return true;
}

}  // namespace swarm_transport
