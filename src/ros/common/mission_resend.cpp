#include "swarm_transport/ros/common/mission_resend.h"

#include <unistd.h>

#include <algorithm>
#include <vector>

#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

constexpr std::uint32_t kResentQueue = 100;

}  // namespace

void MissionResender::Remember(const Mission_Status& status, const core::MissionSpec* order) {
  std::lock_guard<std::mutex> lock(mutex_);
  Mission_Resent& entry = latest_[status.mission_id];
  entry.status = status;
  if (order != nullptr) {  // kept from an earlier status when the robot carries it no more
    entry.order = ToNewMission(*order);
    entry.has_order = true;
  }
  heard_[status.mission_id] = ++remembers_;
  while (latest_.size() > kMaxMissions) {
    const auto oldest =
        std::min_element(heard_.begin(), heard_.end(),
                         [](const auto& a, const auto& b) { return a.second < b.second; });
    latest_.erase(oldest->first);
    heard_.erase(oldest);
  }
}

void MissionResender::Ended(std::uint16_t mission_id) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto it = latest_.find(mission_id);
  if (it == latest_.end()) return;
  const std::uint8_t state = it->second.status.state;
  if (state == Mission_Status::DONE || state == Mission_Status::ABORTED) return;
  latest_.erase(it);
  heard_.erase(mission_id);
}

bool MissionResender::Remembers(std::uint16_t mission_id) const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_.count(mission_id) > 0;
}

std::size_t MissionResender::remembered() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return latest_.size();
}

void MissionResender::Start(ros::NodeHandle nh) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (sub_) return;
  pub_ = nh.advertise<Mission_Resent>(names::kMissionResent, kResentQueue);
  sub_ = nh.subscribe(names::kMissionResendRequest, 10, &MissionResender::OnRequest, this);
}

void MissionResender::OnRequest(const Mission_Resend_Request::ConstPtr& request) {
  std::vector<Mission_Resent> answers;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    const auto it = answered_.find(request->requester);
    // The latched request again (a reconnection) is answered once.
    if (it != answered_.end() && it->second == request->request) return;
    answered_[request->requester] = request->request;
    for (const auto& kv : latest_) answers.push_back(kv.second);
  }
  for (Mission_Resent& answer : answers) {
    answer.requester = request->requester;
    answer.request = request->request;
    pub_.publish(answer);
  }
  if (!answers.empty()) {
    ROS_INFO("%s: re-sent the latest status of %zu mission(s) to %s (request %u)",
             ros::this_node::getName().c_str(), answers.size(), request->requester.c_str(),
             request->request);
  }
}

bool WasStartedBefore(const ros::NodeHandle& private_nh, const std::string& what) {
  std::string before;
  const bool started = private_nh.getParam("instance", before);
  private_nh.setParam("instance", std::to_string(::getpid()) + "@" +
                                      std::to_string(ros::WallTime::now().toSec()) + "|" + what);
  const std::size_t bar = before.find('|');
  return started && bar != std::string::npos && before.substr(bar + 1) == what;
}

void ForgetInstance(const ros::NodeHandle& private_nh) {
  if (ros::ok()) private_nh.deleteParam("instance");
}

}  // namespace swarm_transport
