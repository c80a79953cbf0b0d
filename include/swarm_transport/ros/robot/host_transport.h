// The transports of a host's robots (robot_host). Both leave the swarm-wide topics (the robot
// list and, in real time, the mission topics) to the host, which subscribes them once for all
// its robots and hands each message to every robot on the robot's queue (roscpp asks the master
// five parameters for every subscription callback, so a subscription per robot and topic was
// almost all of a host's start-up), and send diagnostics lines to the host's batch.
// - HostTransport (deploy:=host): the robot's own robot_<id>/neighbors in, robot_<id>/cmd_vel
//   (real time) or robot_<id>/answer (lock-step) out, on the robot's callback queue.
// - DirectTransport (deploy:=host_sim): the simulator of the same process hands the host the
//   robot's rounds (DirectRobots::Deliver) and takes its commands and answers (RobotOutlet,
//   direct_link.h): no per-robot topics.
#ifndef SWARM_TRANSPORT_ROS_HOST_TRANSPORT_H_
#define SWARM_TRANSPORT_ROS_HOST_TRANSPORT_H_

#include <ros/ros.h>

#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "swarm_transport/ros/common/direct_link.h"
#include "swarm_transport/ros/robot/robot_transport.h"

namespace swarm_transport {

// Where a host's robots send their diagnostics lines (thread-safe; outlives the robots).
using StatsSink = std::function<void(const std::string&)>;

class HostTransport : public RobotTransport {
 public:
  HostTransport(StatsSink stats, bool services) : stats_(std::move(stats)), services_(services) {}
  void Connect(ros::NodeHandle nh, const TransportOptions& link, RobotInbox* robot) override;
  void Disconnect() override { neighbors_sub_.shutdown(); }
  void SendAnswer(const Tick_Answer& answer) override { answer_pub_.publish(answer); }
  void SendCommand(const geometry_msgs::Twist& command) override;
  void SendStats(const std::string& line) override { stats_(line); }
  bool OffersServices() const override { return services_; }
  bool SimulatorTurnsOnReceipt() const override { return true; }

 private:
  const StatsSink stats_;
  const bool services_;
  ros::Subscriber neighbors_sub_;
  ros::Publisher cmd_pub_;     // real time
  ros::Publisher answer_pub_;  // lock-step
};

class DirectTransport : public RobotTransport {
 public:
  // `outlet` (the simulator) must outlive the robot.
  DirectTransport(RobotOutlet* outlet, StatsSink stats, bool services)
      : outlet_(outlet), stats_(std::move(stats)), services_(services) {}
  // Its rounds come from the host, which the simulator hands them (RobotHost::Deliver).
  void Connect(ros::NodeHandle /*nh*/, const TransportOptions& link,
               RobotInbox* /*robot*/) override {
    id_ = link.id;
  }
  void Disconnect() override {}
  void SendAnswer(const Tick_Answer& answer) override { outlet_->SendAnswer(id_, answer); }
  void SendCommand(const geometry_msgs::Twist& command) override {
    outlet_->SendCommand(id_, command);
  }
  void SendStats(const std::string& line) override { stats_(line); }
  bool OffersServices() const override { return services_; }
  bool SimulatorTurnsOnReceipt() const override { return true; }

 private:
  RobotOutlet* const outlet_;
  const StatsSink stats_;
  const bool services_;
  std::uint16_t id_ = 0;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_HOST_TRANSPORT_H_
