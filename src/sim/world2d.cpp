#include "swarm_transport/sim/world2d.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <sstream>

namespace swarm_transport {
namespace sim {
namespace {

// A command with less than this left is over (sums of sub-steps leave ~1e-17 s crumbs).
constexpr double kTimeEpsilonS = 1e-9;
// Positions on the arena border count as inside when rounding put them this far out.
constexpr double kInsideToleranceM = 1e-9;

void SetError(std::string* error, const std::string& text) {
  if (error != nullptr) *error = text;
}

bool IsFinite(const core::Pose2& pose) {
  return std::isfinite(pose.position.x) && std::isfinite(pose.position.y) &&
         std::isfinite(pose.heading.degrees());
}

}  // namespace

std::string WorldParams::Validate() const {
  std::ostringstream os;
  if (!std::isfinite(world_size_m) || !(world_size_m > 0.0)) {
    os << "world_size_m must be > 0 but is " << world_size_m;
  } else if (!std::isfinite(robot_radius_m) || !(robot_radius_m > 0.0) ||
             !(2.0 * robot_radius_m < world_size_m)) {
    os << "robot_radius_m must be in (0, world_size_m / 2) but is " << robot_radius_m;
  } else if (!std::isfinite(integration_step_s) || !(integration_step_s > 0.0)) {
    os << "integration_step_s must be > 0 but is " << integration_step_s;
  } else if (!std::isfinite(command_duration_s) || !(command_duration_s > 0.0)) {
    os << "command_duration_s must be > 0 but is " << command_duration_s;
  }
  return os.str();
}

World2D::World2D(const WorldParams& params) : params_(params) {}

bool World2D::Inside(const core::Pose2& pose, std::string* error) const {
  if (!IsFinite(pose)) {
    SetError(error, "the pose must be finite");
    return false;
  }
  const double lo = params_.robot_radius_m - kInsideToleranceM;
  const double hi = params_.world_size_m - params_.robot_radius_m + kInsideToleranceM;
  const core::Vec2 p = pose.position;
  if (p.x < lo || p.x > hi || p.y < lo || p.y > hi) {
    std::ostringstream os;
    os << "(" << p.x << ", " << p.y << ") is outside the arena: x and y must be in ["
       << params_.robot_radius_m << ", " << params_.world_size_m - params_.robot_radius_m << "]";
    SetError(error, os.str());
    return false;
  }
  return true;
}

core::Vec2 World2D::Clamped(core::Vec2 p) const {
  const double lo = params_.robot_radius_m;
  const double hi = params_.world_size_m - params_.robot_radius_m;
  return {std::min(hi, std::max(lo, p.x)), std::min(hi, std::max(lo, p.y))};
}

bool World2D::Spawn(std::uint16_t id, const core::Pose2& pose, std::string* error) {
  if (robots_.count(id) != 0) {
    SetError(error, "robot " + std::to_string(id) + " already exists");
    return false;
  }
  if (!Inside(pose, error)) return false;
  Robot robot;
  robot.id = id;
  robot.pose = pose;
  robot.pose.position = Clamped(pose.position);
  robot.spawn_pose = robot.pose;
  robots_.emplace(id, robot);
  return true;
}

bool World2D::Kill(std::uint16_t id, std::string* error) {
  if (robots_.erase(id) == 0) {
    SetError(error, "robot " + std::to_string(id) + " does not exist");
    return false;
  }
  return true;
}

bool World2D::TeleportAbsolute(std::uint16_t id, const core::Pose2& pose, std::string* error) {
  auto it = robots_.find(id);
  if (it == robots_.end()) {
    SetError(error, "robot " + std::to_string(id) + " does not exist");
    return false;
  }
  if (!Inside(pose, error)) return false;
  it->second.pose = pose;
  it->second.pose.position = Clamped(pose.position);
  return true;
}

bool World2D::TeleportRelative(std::uint16_t id, double linear_m, double angular_rad,
                               std::string* error) {
  auto it = robots_.find(id);
  if (it == robots_.end()) {
    SetError(error, "robot " + std::to_string(id) + " does not exist");
    return false;
  }
  if (!std::isfinite(linear_m) || !std::isfinite(angular_rad)) {
    SetError(error, "linear and angular must be finite");
    return false;
  }
  core::Pose2& pose = it->second.pose;
  pose.heading = pose.heading + core::Angle::FromRadians(angular_rad);
  const double theta = pose.heading.radians();
  pose.position = Clamped(
      {pose.position.x + linear_m * std::cos(theta), pose.position.y + linear_m * std::sin(theta)});
  return true;
}

bool World2D::SetCommand(std::uint16_t id, core::Velocity velocity, std::string* error) {
  auto it = robots_.find(id);
  if (it == robots_.end()) {
    SetError(error, "robot " + std::to_string(id) + " does not exist");
    return false;
  }
  return ApplyCommand(&it->second, velocity, error);
}

bool World2D::SetCommandAt(std::size_t index, core::Velocity velocity, std::string* error) {
  if (index >= robots_.size()) {
    SetError(error, "no robot at index " + std::to_string(index));
    return false;
  }
  return ApplyCommand(&robots_.nth(index)->second, velocity, error);
}

bool World2D::ApplyCommand(Robot* robot, core::Velocity velocity, std::string* error) const {
  if (!std::isfinite(velocity.linear) || !std::isfinite(velocity.angular)) {
    SetError(error, "the velocity must be finite");
    return false;
  }
  // Turn in place at once, then drive straight for the command's duration: the thesis's tick
  // (teleport_relative, then 1 s of driving) and exactly what core::TurnThenDrive predicts.
  robot->pose.heading =
      robot->pose.heading + core::Angle::FromRadians(velocity.angular * params_.command_duration_s);
  robot->command = core::Velocity{velocity.linear, 0.0};
  robot->command_remaining_s = params_.command_duration_s;
  return true;
}

void World2D::Step(double dt_s, bool resolve_contacts) {
  if (!std::isfinite(dt_s) || dt_s < 0.0) return;
  if (dt_s > 0.0) {
    const int substeps =
        std::max(1, static_cast<int>(std::ceil(dt_s / params_.integration_step_s - 1e-9)));
    const double h = dt_s / substeps;
    for (auto& entry : robots_) {
      Robot& robot = entry.second;
      for (int s = 0; s < substeps; ++s) {
        if (robot.command_remaining_s <= 0.0) {
          robot.last_velocity = core::Velocity();
          continue;
        }
        // The last piece of a command is exactly what is left of it, so a command drives for
        // exactly command_duration_s and a robot's prediction matches the simulation.
        const double d = robot.command_remaining_s <= h ? robot.command_remaining_s : h;
        robot.pose = core::Integrate(robot.pose, robot.command, d, &robot.trig);
        robot.last_velocity = robot.command;
        robot.command_remaining_s -= d;
        if (robot.command_remaining_s <= kTimeEpsilonS) {
          robot.command_remaining_s = 0.0;
          robot.command = core::Velocity();
          continue;
        }
        // The straight sub-steps of a whole h that follow, while `trig` holds all they need
        // (the heading a sub-step ends with is then the one it started with): the inline
        // Integrate's expressions without its checks at every sub-step.
        const double turn = robot.command.angular * h;
        if (!(std::fabs(robot.command.angular) < core::kStraightAngularRadPerS) ||
            !robot.trig.Holds(robot.pose.heading.degrees(), turn)) {
          continue;
        }
        const double length = robot.command.linear * h;
        while (s + 1 < substeps && robot.command_remaining_s > h) {
          ++s;
          robot.pose.position = {robot.pose.position.x + length * robot.trig.cos,
                                 robot.pose.position.y + length * robot.trig.sin};
          robot.command_remaining_s -= h;
          if (robot.command_remaining_s <= kTimeEpsilonS) {
            robot.command_remaining_s = 0.0;
            robot.command = core::Velocity();
            break;
          }
        }
      }
      robot.pose.position = Clamped(robot.pose.position);  // ClampAll in the same pass
    }
  } else {
    ClampAll();
  }
  if (resolve_contacts) ResolveContacts();
}

void World2D::Reset() {
  for (auto& entry : robots_) {
    Robot& robot = entry.second;
    robot.pose = robot.spawn_pose;
    robot.command = core::Velocity();
    robot.command_remaining_s = 0.0;
    robot.last_velocity = core::Velocity();
  }
}

const Robot* World2D::Find(std::uint16_t id) const {
  auto it = robots_.find(id);
  return it == robots_.end() ? nullptr : &it->second;
}

}  // namespace sim
}  // namespace swarm_transport
