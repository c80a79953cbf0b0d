// A robot on real hardware (robot.launch hardware:=true, docs/hardware.md): there is no
// simulator, so the transport assembles the robot's round itself at each tick of its own loop -
// its pose from its base (nav_msgs/Odometry on `odom`, or tf of its base frame in a shared
// fixed frame), the other robots' /flock/position over the network put through the
// simulator's radio code (sim::HeardRound) - and sends its command on `cmd_vel` within the
// base's speed limits. A pose older than ~pose_timeout_s stops the robot (zero cmd_vel, said
// once) until poses return. Missions, freeze / continue and statuses travel on the mission
// topics as for any real-time robot; the robot list is the robots it ever heard, and those a
// /flock/robots list names where a node publishes one.
#ifndef SWARM_TRANSPORT_ROS_HARDWARE_TRANSPORT_H_
#define SWARM_TRANSPORT_ROS_HARDWARE_TRANSPORT_H_

#include <nav_msgs/Odometry.h>
#include <ros/ros.h>
#include <tf2_ros/buffer.h>
#include <tf2_ros/transform_listener.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "swarm_transport/core/hardware.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/ros/common/mission_topics.h"
#include "swarm_transport/ros/robot/robot_transport.h"
#include "swarm_transport/ros/robot/tick_loop.h"
#include "swarm_transport/sim/heard_round.h"

namespace swarm_transport {

// Reads a hardware robot's private parameters (~pose_source, ~odom_topic, ~fixed_frame,
// ~base_frame, ~max_linear_m_s, ~max_angular_rad_s, ~pose_timeout_s, ~heard_timeout_s) over
// the defaults in `options` and validates them; false with `error` naming the first bad one.
bool ReadHardwareOptions(const ros::NodeHandle& private_nh, core::HardwareOptions* options,
                         std::string* error);

class HardwareTransport : public RobotTransport {
 public:
  explicit HardwareTransport(const core::HardwareOptions& options) : options_(options) {}
  void Prepare(ros::NodeHandle* nh, ros::NodeHandle* private_nh) override;
  void Connect(ros::NodeHandle nh, const TransportOptions& link, RobotInbox* robot) override;
  void Disconnect() override;
  void SendAnswer(const Tick_Answer& /*answer*/) override {}  // real time only
  void SendCommand(const geometry_msgs::Twist& command) override;
  void SendStats(const std::string& line) override;
  bool Spin(double tick_period_s) override;
  void Stop() override { ticker_.Stop(); }
  bool OwnProcess() const override { return true; }
  bool AnnouncesPosition() const override { return true; }
  int CommandListeners() const override {
    return cmd_pub_ ? static_cast<int>(cmd_pub_.getNumSubscribers()) : -1;
  }

 private:
  void OnOdometry(const nav_msgs::Odometry::ConstPtr& msg);
  // tf: the newest transform of its base frame in the fixed frame, if any.
  void LookUpPose();
  // Its tick is due (the poll thread): a fresh pose gives a round and a tick, a stale one a
  // zero command.
  void OnTickDue();

  const core::HardwareOptions options_;
  RobotInbox* robot_ = nullptr;
  std::uint16_t id_ = 0;
  std::mutex mutex_;  // its handles' callbacks and its ticks
  std::unique_ptr<LockedCallbackQueue> locked_queue_;
  PollThreadTicker ticker_;
  std::optional<sim::HeardRound> heard_;
  std::optional<core::PoseWatch> watch_;
  core::Pose2 pose_;
  core::Velocity velocity_;
  bool roster_changed_ = true;
  std::uint64_t tick_ = 0;
  bool diagnostics_ = false;  // it counts each round's delivery for the robot's figures
  double tick_period_s_ = 0.1;
  core::Round round_;
  std::unique_ptr<tf2_ros::Buffer> tf_buffer_;
  std::unique_ptr<tf2_ros::TransformListener> tf_listener_;
  ros::Subscriber odom_sub_;
  ros::Subscriber position_sub_;
  ros::Subscriber robots_sub_;
  MissionTopics mission_topics_;
  ros::Publisher cmd_pub_;
  ros::Publisher stats_pub_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_HARDWARE_TRANSPORT_H_
