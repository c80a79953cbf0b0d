#include "swarm_transport/ros/robot/hardware_transport.h"

#include <ros/callback_queue.h>
#include <std_msgs/String.h>

#include <chrono>
#include <cmath>

#include "swarm_transport/core/tick_stats.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"
#include "swarm_transport/ros/common/params.h"

namespace swarm_transport {
namespace {

// Every robot announces its position once per tick: the queue holds a large swarm's tick.
constexpr std::uint32_t kPositionQueue = 1000;
constexpr std::uint32_t kOdomQueue = 5;
constexpr std::uint32_t kStatsQueue = 10;

double YawOf(double x, double y, double z, double w) {
  return std::atan2(2.0 * (w * z + x * y), 1.0 - 2.0 * (y * y + z * z));
}

core::Pose2 PoseOf(double x, double y, double yaw) {
  return core::Pose2{{x, y}, core::Angle::FromRadians(yaw)};
}

}  // namespace

bool ReadHardwareOptions(const ros::NodeHandle& private_nh, core::HardwareOptions* options,
                         std::string* error) {
  std::string source = core::PoseSourceName(options->pose_source);
  if (!ReadPrivate(private_nh, "pose_source", &source, error) ||
      !ReadPrivate(private_nh, "odom_topic", &options->odom_topic, error) ||
      !ReadPrivate(private_nh, "fixed_frame", &options->fixed_frame, error) ||
      !ReadPrivate(private_nh, "base_frame", &options->base_frame, error) ||
      !ReadPrivate(private_nh, "max_linear_m_s", &options->max_linear_m_s, error) ||
      !ReadPrivate(private_nh, "max_angular_rad_s", &options->max_angular_rad_s, error) ||
      !ReadPrivate(private_nh, "pose_timeout_s", &options->pose_timeout_s, error) ||
      !ReadPrivate(private_nh, "heard_timeout_s", &options->heard_timeout_s, error)) {
    return false;
  }
  if (private_nh.hasParam("/swarm/radio_loss") &&
      !private_nh.getParam("/swarm/radio_loss", options->radio_loss)) {
    *error = "/swarm/radio_loss must be a number";
    return false;
  }
  if (!core::ParsePoseSource(source, &options->pose_source)) {
    *error = "~pose_source must be odom or tf but is '" + source + "'";
    return false;
  }
  *error = options->Validate();
  return error->empty();
}

void HardwareTransport::Prepare(ros::NodeHandle* nh, ros::NodeHandle* private_nh) {
  // Before anything is connected: every callback of its handles runs under its lock.
  locked_queue_ = std::make_unique<LockedCallbackQueue>(ros::getGlobalCallbackQueue(), &mutex_);
  nh->setCallbackQueue(locked_queue_.get());
  private_nh->setCallbackQueue(locked_queue_.get());
}

void HardwareTransport::Connect(ros::NodeHandle nh, const TransportOptions& link,
                                RobotInbox* robot) {
  robot_ = robot;
  id_ = link.id;
  const SwarmConfig& swarm = *link.swarm;
  sim::RadioParams radio;
  radio.range_m = swarm.flocking.local_range_m;
  radio.hops = swarm.flocking.neighbourhood == core::Neighbourhood::kChain ? swarm.chain_hops : 1;
  radio.loss = options_.radio_loss;
  sim::WorldParams world;
  world.world_size_m = swarm.flocking.world_size_m;
  world.robot_radius_m = swarm.flocking.robot_radius_m;
  heard_.emplace(id_, radio, world, options_.heard_timeout_s, swarm.seed);
  watch_.emplace(options_.pose_timeout_s);
  cmd_pub_ = nh.advertise<geometry_msgs::Twist>(names::kCmdVel, 2);
  if (options_.pose_source == core::PoseSource::kOdom) {
    odom_sub_ = nh.subscribe<nav_msgs::Odometry>(options_.odom_topic, kOdomQueue,
                                                 &HardwareTransport::OnOdometry, this,
                                                 ros::TransportHints().tcpNoDelay());
  } else {
    tf_buffer_ = std::make_unique<tf2_ros::Buffer>();
    tf_listener_ = std::make_unique<tf2_ros::TransformListener>(*tf_buffer_);
  }
  position_sub_ = nh.subscribe<Robot_Position>(
      names::kPosition, kPositionQueue,
      boost::function<void(const Robot_Position::ConstPtr&)>(
          [this](const Robot_Position::ConstPtr& msg) {
            if (heard_->Hear(ToPosition(*msg), ros::WallTime::now().toSec())) {
              roster_changed_ = true;
            }
          }),
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
  // A robot list, where a node publishes one (the stand-in; on robots, the core machine may):
  // those robots are known before they are heard.
  robots_sub_ = nh.subscribe<Robot_Positions>(
      names::kRobots, 2,
      boost::function<void(const Robot_Positions::ConstPtr&)>(
          [this](const Robot_Positions::ConstPtr& msg) {
            for (const Robot_Position& r : msg->robots) {
              if (r.type == Robot_Position::TYPE_PHYSICAL && heard_->Know(r.robot_id)) {
                roster_changed_ = true;
              }
            }
          }));
  mission_topics_.Subscribe(nh,
                            [this](const core::MissionMessage& message, const core::Sender& from) {
                              heard_->Take(message);  // the mission channel of its missions' robots
                              robot_->Hand(message, from);
                            });
  diagnostics_ = link.diagnostics;
  tick_period_s_ = swarm.tick_period_s;
  if (link.diagnostics)
    stats_pub_ = nh.advertise<std_msgs::String>(names::kRobotStats, kStatsQueue);
  ROS_INFO(
      "robot %u: hardware: pose from %s, cmd_vel within %.3f m/s and %.3f rad/s, stands "
      "on a pose older than %.2f s, hears positions up to %.2f s old (radio range %.3f m, "
      "%d hop(s), loss %.3f)",
      id_,
      options_.pose_source == core::PoseSource::kOdom
          ? nh.resolveName(options_.odom_topic).c_str()
          : (options_.base_frame + " in " + options_.fixed_frame + " (tf)").c_str(),
      options_.max_linear_m_s, options_.max_angular_rad_s, options_.pose_timeout_s,
      options_.heard_timeout_s, radio.range_m, radio.hops, radio.loss);
}

void HardwareTransport::Disconnect() {
  ticker_.Stop();
  odom_sub_.shutdown();
  position_sub_.shutdown();
  robots_sub_.shutdown();
  mission_topics_.Shutdown();
  tf_listener_.reset();
}

void HardwareTransport::OnOdometry(const nav_msgs::Odometry::ConstPtr& msg) {
  const auto& p = msg->pose.pose;
  const double yaw = YawOf(p.orientation.x, p.orientation.y, p.orientation.z, p.orientation.w);
  if (!std::isfinite(p.position.x) || !std::isfinite(p.position.y) || !std::isfinite(yaw)) return;
  pose_ = PoseOf(p.position.x, p.position.y, yaw);
  velocity_ = {msg->twist.twist.linear.x, msg->twist.twist.angular.z};
  // A driver that does not stamp its odometry: the pose is as old as its arrival.
  watch_->Took(msg->header.stamp.isZero() ? ros::Time::now().toSec() : msg->header.stamp.toSec());
}

void HardwareTransport::LookUpPose() {
  try {
    const geometry_msgs::TransformStamped t =
        tf_buffer_->lookupTransform(options_.fixed_frame, options_.base_frame, ros::Time(0));
    const auto& q = t.transform.rotation;
    const double yaw = YawOf(q.x, q.y, q.z, q.w);
    if (!std::isfinite(t.transform.translation.x) || !std::isfinite(t.transform.translation.y) ||
        !std::isfinite(yaw)) {
      return;
    }
    pose_ = PoseOf(t.transform.translation.x, t.transform.translation.y, yaw);
    velocity_ = {};
    watch_->Took(t.header.stamp.toSec());
  } catch (const tf2::TransformException&) {
    // No transform (yet): the pose ages, and the watch stops the robot.
  }
}

void HardwareTransport::SendCommand(const geometry_msgs::Twist& command) {
  if (!cmd_pub_) return;
  const core::Velocity limited =
      core::LimitSpeed(ToVelocity(command), options_.max_linear_m_s, options_.max_angular_rad_s);
  cmd_pub_.publish(ToTwist(limited));
}

void HardwareTransport::SendStats(const std::string& line) {
  std_msgs::String msg;
  msg.data = line;
  stats_pub_.publish(msg);
}

bool HardwareTransport::Spin(double tick_period_s) {
  return SpinWithOwnTicks(
      &ticker_, tick_period_s, [this] { OnTickDue(); }, id_);
}

void HardwareTransport::OnTickDue() {
  std::lock_guard<std::mutex> lock(mutex_);
  const double now_s = ros::Time::now().toSec();
  if (tf_buffer_) LookUpPose();
  core::PoseWatch::Change change = core::PoseWatch::Change::kNone;
  const bool fresh = watch_->Check(now_s, &change);
  if (change == core::PoseWatch::Change::kStale) {
    ROS_WARN("robot %u: no pose for %.2f s (~pose_timeout_s %.2f): it stands until poses return",
             id_, watch_->AgeS(now_s), options_.pose_timeout_s);
  } else if (change == core::PoseWatch::Change::kFresh && tick_ > 0) {
    ROS_INFO("robot %u: poses are back: it moves again", id_);
  }
  if (!fresh) {
    cmd_pub_.publish(geometry_msgs::Twist());
    return;
  }
  if (roster_changed_) {
    roster_changed_ = false;
    Robot_Positions list;
    for (std::uint16_t known : heard_->known()) {
      Robot_Position r;
      r.robot_id = known;
      list.robots.push_back(r);
    }
    robot_->HearRobots(list);
  }
  heard_->Assemble(++tick_, now_s, pose_, velocity_, &round_);
  if (diagnostics_) {
    // Delivered: a robot's latest position arrived within the late-tick margin of one period
    // (each sends one per tick), as the bench counts it for the simulator's radio.
    const std::pair<std::size_t, std::size_t> d =
        heard_->Delivered(round_, now_s, core::kLateTickFactor * tick_period_s_);
    robot_->CountDelivered(d.first, d.second);
  }
  robot_->TakeRound(boost::make_shared<Neighbors>(ToNeighbors(round_)), now_s);
  robot_->TimerTick();
}

}  // namespace swarm_transport
