// A recorder restarted on the same master (docs/reliability.md, "The recorder restarts"): it
// appends to the run's files after a gap comment, takes over the earlier recorder's rows and
// counts, and records the missions the first leaders re-send.
#include <cmath>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <system_error>

#include "swarm_transport/Mission_Resend_Request.h"
#include "swarm_transport/core/record_resume.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"
#include "swarm_transport/ros/recorder/recorder.h"

namespace swarm_transport {
namespace {

constexpr char kNode[] = "recorder";
constexpr std::uint32_t kResentQueue = 1000;
// Requests at these wall seconds after the start: a first leader whose connection came late
// answers a later one (each is answered once; re-sent statuses already recorded change nothing).
constexpr double kRequestAtS[] = {0.0, 0.5, 1.0, 2.0, 4.0};

// The file's text ("" when it does not exist).
std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string WallNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof(text), "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

}  // namespace

bool Recorder::OpenFilesAgain(std::string* error) {
  const std::string missions = run_dir_ + "/missions.csv";
  const std::string swarm = run_dir_ + "/swarm_count.csv";
  const std::string missions_text = ReadText(missions);
  const std::string swarm_text = ReadText(swarm);
  core::EarlierRecord earlier;
  if (!core::ReadEarlierRecord(missions_text, ReadText(run_dir_ + "/run.csv"), swarm_text, &earlier,
                               error)) {
    *error = "restarted: cannot append to the files in " + run_dir_ + ": " + *error;
    return false;
  }
  // A last line the kill cut short goes; a file without its header gets one.
  for (const auto& file :
       {std::make_pair(missions, &missions_text), std::make_pair(swarm, &swarm_text)}) {
    std::error_code ec;
    if (std::filesystem::exists(file.first, ec)) {
      std::filesystem::resize_file(file.first, core::CompleteLength(*file.second), ec);
    }
  }
  const bool missions_headed = core::CompleteLength(missions_text) > 0;
  const bool swarm_headed = core::CompleteLength(swarm_text) > 0;
  if (!missions_csv_.OpenToAppend(missions, error) || !swarm_csv_.OpenToAppend(swarm, error)) {
    return false;
  }
  if (!missions_headed) missions_csv_.Append(core::RunMetrics::kMissionsHeader);
  if (!swarm_headed) swarm_csv_.Append(core::RunMetrics::kSwarmHeader);
  const std::string gap = core::GapComment(earlier.last_tick, WallNow());
  missions_csv_.Append(gap);
  swarm_csv_.Append(gap);
  gap_open_ = true;
  for (std::uint16_t id : earlier.rows) metrics_->MarkRowWritten(id);
  metrics_->Carry(earlier.samples, earlier.swarm_count_sum, earlier.done, earlier.aborted);
  ROS_WARN(
      "%s: restarted: appending to %s after a gap comment (%zu mission rows, %zu samples "
      "before it)",
      kNode, run_dir_.c_str(), earlier.rows.size(), earlier.samples);
  WriteRun();
  return true;
}

void Recorder::EndGap(std::uint64_t tick) {
  gap_open_ = false;
  if (run_dir_.empty()) return;
  const std::string resumed = core::ResumedComment(tick);
  missions_csv_.Append(resumed);
  swarm_csv_.Append(resumed);
}

void Recorder::RequestResends() {
  resent_sub_ = nh_.subscribe(names::kMissionResent, kResentQueue, &Recorder::OnResent, this);
  request_pub_ = nh_.advertise<Mission_Resend_Request>(names::kMissionResendRequest, 1, true);
  const ros::WallTime start = ros::WallTime::now();
  const auto send = [this, start](const ros::WallTimerEvent&) {
    constexpr std::size_t kRequests = sizeof(kRequestAtS) / sizeof(kRequestAtS[0]);
    if (requests_ >= kRequests || (ros::WallTime::now() - start).toSec() < kRequestAtS[requests_]) {
      return;
    }
    Mission_Resend_Request request;
    request.requester = ros::this_node::getName();
    request.request = ++requests_;
    request_pub_.publish(request);
  };
  send(ros::WallTimerEvent());
  request_timer_ = nh_.createWallTimer(ros::WallDuration(0.1), send);
}

void Recorder::OnResent(const Mission_Resent::ConstPtr& msg) {
  const Mission_Status& st = msg->status;
  if (st.state > Mission_Status::REJECTED || !std::isfinite(st.object_position_x) ||
      !std::isfinite(st.object_position_y)) {
    return;
  }
  std::optional<core::MissionSpec> order;
  if (msg->has_order && msg->order.mission_id == st.mission_id) order = ToMissionSpec(msg->order);
  const std::string warning = metrics_->AddResent(
      order ? &*order : nullptr, st.mission_id, static_cast<core::MissionPhase>(st.state), st.tick,
      {st.object_position_x, st.object_position_y});
  if (!warning.empty() && bad_mission_warning_.Due()) ROS_WARN("%s: %s", kNode, warning.c_str());
  WriteMissions(true);
}

}  // namespace swarm_transport
