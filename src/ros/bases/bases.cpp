#include "swarm_transport/ros/bases/bases.h"

#include <nav_msgs/Odometry.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

constexpr double kMaxOdomRateHz = 1000.0;
// The longest wall time one step of the bases covers (a process held up does not jump them).
constexpr double kMaxStepS = 0.1;

geometry_msgs::Quaternion Yaw(double yaw) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(yaw / 2.0);
  q.w = std::cos(yaw / 2.0);
  return q;
}

}  // namespace

std::string BasesParams::Validate() const {
  std::ostringstream os;
  const std::string swarm_error = swarm.Validate();
  if (!swarm_error.empty()) {
    os << "/swarm: " << swarm_error;
  } else if (robots < 0 || robots > 65535) {
    os << "~robots must be in [0, 65535] but is " << robots;
  } else if (placement == core::Placement::kFile && placement_file.empty()) {
    os << "~placement_file must name a file with ~placement file";
  } else if (!std::isfinite(odom_rate_hz) || odom_rate_hz <= 0.0 || odom_rate_hz > kMaxOdomRateHz) {
    os << "~odom_rate_hz must be in (0, " << kMaxOdomRateHz << "] Hz but is " << odom_rate_hz;
  } else if (!std::isfinite(integration_step_s) || integration_step_s <= 0.0 ||
             integration_step_s > swarm.tick_period_s) {
    os << "~integration_step_s must be in (0, tick_period_s = " << swarm.tick_period_s
       << "] but is " << integration_step_s;
  } else if (fixed_frame.empty()) {
    os << "~fixed_frame must name a frame";
  } else {
    os << noise.Validate();
  }
  return os.str();
}

bool ReadBasesParams(const ros::NodeHandle& nh, const ros::NodeHandle& p, BasesParams* params,
                     std::string* error) {
  XmlRpc::XmlRpcValue swarm;
  if (nh.getParam("/swarm", swarm) && !ConfigFromXmlRpc(swarm, &params->swarm, error)) {
    *error = "/swarm: " + *error;
    return false;
  }
  if (!ReadPrivate(p, "placement", &params->placement, error)) return false;
  if (params->placement == core::Placement::kFile) params->robots = -1;  // every line
  if (!ReadPrivate(p, "robots", &params->robots, error) ||
      !ReadPrivate(p, "placement_file", &params->placement_file, error) ||
      !ReadPrivate(p, "odom_rate_hz", &params->odom_rate_hz, error) ||
      !ReadPrivate(p, "integration_step_s", &params->integration_step_s, error) ||
      !ReadPrivate(p, "position_noise_m", &params->noise.position_noise_m, error) ||
      !ReadPrivate(p, "heading_noise_deg", &params->noise.heading_noise_deg, error) ||
      !ReadPrivate(p, "heading_drift_deg", &params->noise.heading_drift_deg, error) ||
      !ReadPrivate(p, "frame_prefix", &params->frame_prefix, error) ||
      !ReadPrivate(p, "fixed_frame", &params->fixed_frame, error) ||
      !ReadPrivate(p, "tf", &params->tf, error) ||
      !ReadPrivate(p, "events_file", &params->events_file, error) ||
      !ReadPrivate(p, "positions", &params->positions, error)) {
    return false;
  }
  // A placement file with robots unset: every line (PlaceInitialRobots sets the number).
  if (params->robots == -1 && params->placement == core::Placement::kFile) {
    const int robots = params->robots;
    params->robots = 0;
    *error = params->Validate();
    params->robots = robots;
  } else {
    *error = params->Validate();
  }
  return error->empty();
}

std::string Bases::Frame(std::uint16_t id, const char* frame) const {
  return params_.frame_prefix + std::to_string(id) + "/" + frame;
}

bool Bases::Initialize() {
  std::string error;
  bool ok = ReadBasesParams(nh_, private_nh_, &params_, &error);
  if (ok && !params_.events_file.empty()) {
    ok = ReadEventsFile(params_.events_file, &events_, &error);
    for (const TimedEvent& e : events_) {
      if (!ok) break;
      if (e.kind != TimedEvent::Kind::kOdomStop && e.kind != TimedEvent::Kind::kFreeze &&
          e.kind != TimedEvent::Kind::kContinue) {
        ok = false;
        error = "the stand-in plays only odom_stop, freeze and continue events";
      }
    }
    if (!ok) error = "~events_file: " + error;
  }
  sim::WorldParams world;
  world.world_size_m = params_.swarm.flocking.world_size_m;
  world.robot_radius_m = params_.swarm.flocking.robot_radius_m;
  world.integration_step_s = params_.integration_step_s;
  world.command_duration_s = params_.swarm.tick_period_s;  // a command is one tick's move
  if (ok) {
    world_ = std::make_unique<sim::World2D>(world);
    ok = sim::PlaceInitialRobots(params_.placement, params_.swarm.seed, params_.placement_file,
                                 &params_.robots, world_.get(), &error);
  }
  if (!ok) {
    ROS_FATAL("bases: invalid parameters: %s", error.c_str());
    return false;
  }
  schedule_ = std::make_unique<EventSchedule>(events_);
  if (params_.positions) {
    positions_pub_ = nh_.advertise<Robot_Positions>(names::kWorldPoses, 10, true);
    robots_pub_ = nh_.advertise<Robot_Positions>(names::kRobots, 1, true);
  }
  mission_pubs_.Advertise(nh_);  // the schedule's freeze and continue
  Robot_Positions list;
  std::vector<geometry_msgs::TransformStamped> statics;
  for (const auto& entry : world_->robots()) {
    const std::uint16_t id = entry.first;
    list.robots.push_back(ToRobotPosition(id, entry.second.pose));
    noise_.emplace(id, sim::BaseNoise(params_.noise, params_.swarm.seed, id));
    ros::NodeHandle robot_nh(nh_, names::RobotNamespace(id));
    odom_pubs_[id] = robot_nh.advertise<nav_msgs::Odometry>("odom", 5);
    cmd_subs_.push_back(robot_nh.subscribe<geometry_msgs::Twist>(
        names::kCmdVel, 2,
        boost::function<void(const geometry_msgs::Twist::ConstPtr&)>(
            [this, id](const geometry_msgs::Twist::ConstPtr& m) { OnCmdVel(id, *m); }),
        ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay()));
    // Every odometry frame is the shared frame: the stand-in's odometry is in arena coordinates
    // (a lab's localisation or motion capture gives map -> odom).
    geometry_msgs::TransformStamped t;
    t.header.stamp = ros::Time::now();
    t.header.frame_id = params_.fixed_frame;
    t.child_frame_id = Frame(id, "odom");
    t.transform.rotation.w = 1.0;
    statics.push_back(t);
  }
  if (params_.positions) robots_pub_.publish(list);
  if (params_.tf) {
    tf_ = std::make_unique<tf2_ros::TransformBroadcaster>();
    static_tf_ = std::make_unique<tf2_ros::StaticTransformBroadcaster>();
    static_tf_->sendTransform(statics);
  }
  ROS_INFO(
      "bases: %d kinematic bases, odometry at %.1f Hz (noise: %.3f m, %.2f deg; heading "
      "drift %.2f deg per tick), tick %.3f s, %zu timed event(s)",
      params_.robots, params_.odom_rate_hz, params_.noise.position_noise_m,
      params_.noise.heading_noise_deg, params_.noise.heading_drift_deg, params_.swarm.tick_period_s,
      events_.size());
  return true;
}

void Bases::OnCmdVel(std::uint16_t id, const geometry_msgs::Twist& msg) {
  if (!IsFinite(msg)) {
    ROS_WARN_THROTTLE(10.0, "bases: robot %u: rejected a non-finite cmd_vel", id);
    return;
  }
  world_->SetCommand(id, ToVelocity(msg), nullptr);
}

void Bases::BeginTick(double since_start_s) {
  world_->ResolveContacts();
  for (const TimedEvent& e : schedule_->Due(tick_)) {
    if (e.kind == TimedEvent::Kind::kOdomStop) {
      silent_until_[e.robot] = tick_ + e.ticks;
      ROS_INFO("bases: tick %llu: robot %u sends no odometry for %llu ticks",
               static_cast<unsigned long long>(tick_), e.robot,
               static_cast<unsigned long long>(e.ticks));
    } else if (e.kind == TimedEvent::Kind::kFreeze) {
      mission_pubs_.Publish(core::MissionMessage{core::Freeze{e.from, e.to}});
    } else if (e.kind == TimedEvent::Kind::kContinue) {
      mission_pubs_.Publish(core::MissionMessage{core::Continue{e.from, e.to}});
    }
  }
  if (params_.noise.heading_drift_deg > 0.0) {
    for (const auto& entry : world_->robots()) {
      const core::Pose2 pose = entry.second.pose;
      world_->TeleportAbsolute(
          entry.first, {pose.position, noise_.at(entry.first).Drift(pose.heading)}, nullptr);
    }
  }
  if (!params_.positions) return;
  auto all = boost::make_shared<Robot_Positions>();
  all->tick = tick_;
  all->sim_time = since_start_s;
  for (const auto& entry : world_->robots())
    all->robots.push_back(ToRobotPosition(entry.first, entry.second.pose));
  positions_pub_.publish(all);
}

void Bases::PublishOdometry() {
  const ros::Time now = ros::Time::now();
  std::vector<geometry_msgs::TransformStamped> transforms;
  for (const auto& entry : world_->robots()) {
    const std::uint16_t id = entry.first;
    const auto silent = silent_until_.find(id);
    if (silent != silent_until_.end() && tick_ < silent->second) continue;
    const core::Pose2 measured = noise_.at(id).Measure(entry.second.pose);
    nav_msgs::Odometry odom;
    odom.header.stamp = now;
    odom.header.frame_id = Frame(id, "odom");
    odom.child_frame_id = Frame(id, "base_link");
    odom.pose.pose.position.x = measured.position.x;
    odom.pose.pose.position.y = measured.position.y;
    odom.pose.pose.orientation = Yaw(measured.heading.radians());
    odom.twist.twist.linear.x = entry.second.last_velocity.linear;
    odom.twist.twist.angular.z = entry.second.last_velocity.angular;
    odom_pubs_[id].publish(odom);
    if (!tf_) continue;
    geometry_msgs::TransformStamped t;
    t.header = odom.header;
    t.child_frame_id = odom.child_frame_id;
    t.transform.translation.x = measured.position.x;
    t.transform.translation.y = measured.position.y;
    t.transform.rotation = odom.pose.pose.orientation;
    transforms.push_back(t);
  }
  if (tf_ && !transforms.empty()) tf_->sendTransform(transforms);
}

void Bases::Run() {
  ros::WallRate rate(params_.odom_rate_hz);
  const ros::WallTime start = ros::WallTime::now();
  const ros::WallDuration tick(params_.swarm.tick_period_s);
  ros::WallTime next_tick = start;
  ros::WallTime last = start;
  while (ros::ok()) {
    ros::spinOnce();
    const ros::WallTime now = ros::WallTime::now();
    world_->Step(std::min(kMaxStepS, (now - last).toSec()), /*resolve_contacts=*/false);
    last = now;
    if (now >= next_tick) {
      BeginTick((now - start).toSec());
      ++tick_;
      next_tick += tick;
      if (next_tick < now) next_tick = now + tick;  // fell behind: skip, do not burst
    }
    PublishOdometry();
    rate.sleep();
  }
  ROS_INFO("bases: finished after %llu ticks", static_cast<unsigned long long>(tick_));
}

}  // namespace swarm_transport
