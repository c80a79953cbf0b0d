#include "swarm_transport/ros/common/diagnostics.h"

#include <diagnostic_msgs/DiagnosticArray.h>

#include <sstream>

#include "swarm_transport/ros/common/connection_reaper.h"

namespace swarm_transport {
namespace {

constexpr double kPeriodS = 1.0;

}  // namespace

void NodeStatus::Add(const std::string& key, double value) {
  std::ostringstream os;
  os << value;
  values.emplace_back(key, os.str());
}

NodeDiagnostics::NodeDiagnostics(ros::NodeHandle nh, std::string name, std::string hardware_id)
    : pub_(nh.advertise<diagnostic_msgs::DiagnosticArray>("/diagnostics", 10)),
      name_(std::move(name)),
      hardware_id_(std::move(hardware_id)) {}

void NodeDiagnostics::PublishIfDue(const std::function<void(NodeStatus*)>& fill) {
  const ros::WallTime now = ros::WallTime::now();
  if (!last_.isZero() && (now - last_).toSec() < kPeriodS) return;
  last_ = now;
  NodeStatus status;
  fill(&status);
  // roscpp's connections (connection_reaper.h): the held dropped ones stay 0 while the node's
  // ConnectionReaper runs; the reaped ones count what roscpp would have kept.
  const HeldConnections held = ConnectionReaper::Held();
  status.Add("roscpp connections", static_cast<std::uint64_t>(held.held));
  status.Add("roscpp dropped connections held", static_cast<std::uint64_t>(held.dropped));
  status.Add("roscpp dropped connections reaped", ConnectionReaper::Reaped());
  diagnostic_msgs::DiagnosticArray array;
  array.header.stamp = ros::Time::now();
  diagnostic_msgs::DiagnosticStatus s;
  s.level = status.level;
  s.name = name_;
  s.message = status.message;
  s.hardware_id = hardware_id_;
  for (const auto& kv : status.values) {
    diagnostic_msgs::KeyValue v;
    v.key = kv.first;
    v.value = kv.second;
    s.values.push_back(v);
  }
  array.status.push_back(s);
  pub_.publish(array);
}

}  // namespace swarm_transport
