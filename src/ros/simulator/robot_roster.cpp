#include "swarm_transport/ros/simulator/robot_roster.h"

#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/ros/common/conversions.h"
#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {
namespace {

// The stream of the seed's generator that draws the poses of robots joining by New_Robot.
constexpr std::uint64_t kSpawnStream = 0x737061776eULL;  // "spawn"

// A teleport service's answer: OK, or ERROR with the reason (also logged).
template <typename Response>
bool Reply(bool ok, const char* service, std::uint16_t id, const std::string& error,
           Response* res) {
  if (!ok) ROS_WARN("simulator: %s of robot %u rejected: %s", service, id, error.c_str());
  res->code = ok ? Response::OK : Response::ERROR;
  res->message = ok ? "ok" : error;
  return true;
}

}  // namespace

RobotRoster::RobotRoster(sim::World2D* world, RobotLinks* links, LockstepSession* session,
                         DirectRobots* direct, std::uint64_t seed, const std::uint64_t* tick)
    : world_(world),
      links_(links),
      session_(session),
      direct_(direct),
      tick_(tick),
      spawn_rng_(seed, kSpawnStream) {}

void RobotRoster::Connect(ros::NodeHandle nh, std::uint32_t position_queue, std::uint32_t queue) {
  robots_pub_ = nh.advertise<Robot_Positions>(names::kRobots, 1, true);
  spawn_srv_ = nh.advertiseService(names::kSpawn, &RobotRoster::OnSpawn, this);
  kill_srv_ = nh.advertiseService(names::kKill, &RobotRoster::OnKill, this);
  reset_srv_ = nh.advertiseService(names::kReset, &RobotRoster::OnReset, this);
  // /flock/position also carries every robot's own position each tick; we only keep virtual
  // copies (in real time those a robot announces on its own position too) and statists, but the
  // queue must hold a whole tick of the swarm.
  position_sub_ = nh.subscribe(names::kPosition, position_queue, &RobotRoster::OnPosition, this,
                               ros::TransportHints().tcpNoDelay());
  robot_new_sub_ = nh.subscribe(names::kRobotNew, queue, &RobotRoster::OnRobotNew, this);
  robot_delete_sub_ = nh.subscribe(names::kRobotDelete, queue, &RobotRoster::OnRobotDelete, this);
}

void RobotRoster::Shutdown() {
  position_sub_.shutdown();
  robot_new_sub_.shutdown();
  robot_delete_sub_.shutdown();
  spawn_srv_.shutdown();
  kill_srv_.shutdown();
  reset_srv_.shutdown();
}

void RobotRoster::Add(std::uint16_t id) {
  links_->Add(id);
  if (session_) session_->AddRobot(id);
}

void RobotRoster::Remove(std::uint16_t id) {
  world_->Kill(id, nullptr);
  links_->Remove(id);
  if (session_) session_->RemoveRobot(id);
  if (direct_ != nullptr && direct_->Hosts(id)) direct_->Release(id);
  relayed_.EraseCopiesOf(id);  // its virtual copies die with it
}

std::string RobotRoster::Spawn(std::uint16_t id, const core::Pose2& pose) {
  std::string error;
  if (!world_->Spawn(id, pose, &error)) {
    ROS_WARN("simulator: spawn of robot %u rejected: %s", id, error.c_str());
    return error;
  }
  PublishList();  // first: a robot started now finds itself listed
  // A host of many robots that runs this simulator starts the robot itself.
  if (direct_ != nullptr && !direct_->Hosts(id)) direct_->Adopt(id);
  Add(id);
  ROS_INFO("simulator: spawned robot %u at (%.3f, %.3f, %.1f deg)", id, pose.position.x,
           pose.position.y, pose.heading.degrees());
  return "";
}

void RobotRoster::KillByEvent(std::uint16_t id) {
  if (world_->Find(id) == nullptr) {
    ROS_WARN("simulator: timed kill of robot %u at tick %llu: no such robot", id,
             static_cast<unsigned long long>(*tick_));
    return;
  }
  Remove(id);
  PublishList();
  ROS_INFO("simulator: killed robot %u (timed event, tick %llu)", id,
           static_cast<unsigned long long>(*tick_));
}

void RobotRoster::PublishList() {
  Robot_Positions list;
  list.tick = *tick_;
  for (const auto& entry : world_->robots()) {
    list.robots.push_back(ToRobotPosition(entry.first, entry.second.pose));
  }
  robots_pub_.publish(list);
}

bool RobotRoster::OnSpawn(Spawn::Request& req, Spawn::Response& res) {
  const core::Pose2 pose{{req.x, req.y}, core::Angle::FromRadians(req.theta)};
  const std::string error = Spawn(req.robot_id, pose);
  if (!error.empty()) {
    res.code = Spawn::Response::ERROR;
    res.message = error;
    return true;
  }
  res.code = Spawn::Response::OK;
  res.message = "spawned robot " + std::to_string(req.robot_id);
  return true;
}

bool RobotRoster::OnKill(Kill::Request& req, Kill::Response& res) {
  if (world_->Find(req.robot_id) == nullptr) {
    res.code = Kill::Response::ERROR;
    res.message = "robot " + std::to_string(req.robot_id) + " does not exist";
    ROS_WARN("simulator: kill rejected: %s", res.message.c_str());
    return true;
  }
  Remove(req.robot_id);
  PublishList();
  ROS_INFO("simulator: killed robot %u", req.robot_id);
  res.code = Kill::Response::OK;
  res.message = "killed robot " + std::to_string(req.robot_id);
  return true;
}

bool RobotRoster::OnReset(std_srvs::Empty::Request& /*req*/, std_srvs::Empty::Response& /*res*/) {
  world_->Reset();
  ROS_INFO("simulator: reset %zu robots to their spawn poses", world_->size());
  return true;
}

bool RobotRoster::OnTeleportAbsolute(std::uint16_t id, TeleportAbsolute::Request& req,
                                     TeleportAbsolute::Response& res) {
  std::string error;
  const core::Pose2 pose{{req.x, req.y}, core::Angle::FromRadians(req.theta)};
  return Reply(world_->TeleportAbsolute(id, pose, &error), "teleport_absolute", id, error, &res);
}

bool RobotRoster::OnTeleportRelative(std::uint16_t id, TeleportRelative::Request& req,
                                     TeleportRelative::Response& res) {
  std::string error;
  return Reply(world_->TeleportRelative(id, req.linear, req.angular, &error), "teleport_relative",
               id, error, &res);
}

void RobotRoster::OnPosition(const Robot_Position::ConstPtr& msg) {
  // Lock-step: a robot's answer carries the copies it announces (the engine's), so that the
  // round does not depend on when its position arrived; real time: its position.
  if (session_ != nullptr && msg->type == Robot_Position::TYPE_PHYSICAL) return;
  const std::string why = relayed_.Take(ToPosition(*msg));
  if (!why.empty() && bad_position_warning_.Due()) {
    ROS_WARN("simulator: rejected a Robot_Position of robot %u/%u: %s%s", msg->robot_id,
             msg->sub_id, why.c_str(), bad_position_warning_.AndMore("rejected").c_str());
  }
}

void RobotRoster::OnRobotNew(const New_Robot::ConstPtr& msg) {
  if (msg->type != Robot_Position::TYPE_PHYSICAL) {
    ROS_DEBUG("simulator: New_Robot %u/%u of type %u: it joins by announcing itself on %s",
              msg->robot_id, msg->sub_id, msg->type, names::kPosition);
    return;
  }
  if (world_->Find(msg->robot_id) != nullptr) {
    ROS_INFO("simulator: New_Robot %u: it is in the swarm already", msg->robot_id);
    return;
  }
  core::Pose2 pose;
  if (!sim::FreePose(*world_, &spawn_rng_, &pose)) {
    ROS_WARN("simulator: New_Robot %u rejected: no free place in the arena", msg->robot_id);
    return;
  }
  Spawn(msg->robot_id, pose);
}

void RobotRoster::OnRobotDelete(const Delete_Robot::ConstPtr& msg) {
  if (relayed_.Erase(msg->robot_id, msg->sub_id)) return;
  if (msg->sub_id == 0 && world_->Find(msg->robot_id) != nullptr) {
    Remove(msg->robot_id);
    PublishList();
    ROS_INFO("simulator: Delete_Robot %u: the robot left the swarm", msg->robot_id);
    return;
  }
  if (bad_delete_warning_.Due()) {
    ROS_WARN("simulator: Delete_Robot %u/%u: no such robot, virtual copy or statist%s",
             msg->robot_id, msg->sub_id, bad_delete_warning_.AndMore("such messages").c_str());
  }
}

}  // namespace swarm_transport
