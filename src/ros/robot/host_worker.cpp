#include "swarm_transport/ros/robot/host_worker.h"

#include <std_msgs/String.h>

#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {

namespace {
constexpr double kStatsBatchS = 0.05;
// Messages, not lines: a subscriber that lags a few seconds still gets every line.
constexpr std::uint32_t kStatsBatchQueue = 100;
}  // namespace

StatsBatch::StatsBatch(ros::NodeHandle nh)
    : pub_(nh.advertise<std_msgs::String>(names::kRobotStats, kStatsBatchQueue)),
      last_(ros::WallTime::now()) {}

void StatsBatch::Add(const std::string& line) {
  std::lock_guard<std::mutex> lock(mutex_);
  if (!lines_.empty()) lines_ += '\n';
  lines_ += line;
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_).toSec() >= kStatsBatchS) FlushLocked(now);
}

void StatsBatch::FlushIfDue() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (lines_.empty()) return;
  const ros::WallTime now = ros::WallTime::now();
  if ((now - last_).toSec() >= kStatsBatchS) FlushLocked(now);
}

void StatsBatch::FlushLocked(const ros::WallTime& now) {
  auto msg = boost::make_shared<std_msgs::String>();
  msg->data.swap(lines_);
  pub_.publish(msg);
  last_ = now;
}

}  // namespace swarm_transport
