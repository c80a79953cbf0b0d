// One diagnostic status per node on /diagnostics (diagnostic_msgs/DiagnosticArray), as rqt's
// monitors and the diagnostic aggregator expect: at most once per wall second, named after the
// node, with its figures as key-values. (Debian has diagnostic_msgs but not diagnostic_updater;
// this is the part of it a node of this package needs.)
#ifndef SWARM_TRANSPORT_ROS_DIAGNOSTICS_H_
#define SWARM_TRANSPORT_ROS_DIAGNOSTICS_H_

#include <diagnostic_msgs/DiagnosticStatus.h>
#include <ros/ros.h>

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace swarm_transport {

struct NodeStatus {
  std::uint8_t level = diagnostic_msgs::DiagnosticStatus::OK;  // OK, WARN, ERROR, STALE
  std::string message;  // one line: what the node is doing / what is wrong
  std::vector<std::pair<std::string, std::string>> values;
  void Add(const std::string& key, const std::string& value) { values.emplace_back(key, value); }
  void Add(const std::string& key, double value);
  void Add(const std::string& key, std::uint64_t value) { Add(key, std::to_string(value)); }
};

class NodeDiagnostics {
 public:
  // `name`: the status's name ("swarm_transport: simulator"); `hardware_id`: what it runs on.
  NodeDiagnostics(ros::NodeHandle nh, std::string name, std::string hardware_id = "");
  // Publishes `fill`'s status when a wall second passed since the last one (cheap otherwise:
  // `fill` is not called).
  void PublishIfDue(const std::function<void(NodeStatus*)>& fill);

 private:
  ros::Publisher pub_;
  std::string name_;
  std::string hardware_id_;
  ros::WallTime last_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_DIAGNOSTICS_H_
