// In-process links between a simulator and the robots hosted in the same process: the per-robot
// topics neighbors, cmd_vel and (lock-step) answer without roscpp in between.
//
// Why: every roscpp publication of a process is locked by its poll loop each cycle, and every
// Publisher::publish looks its topic up by a linear search over all of the process's
// publications. With a few per-robot topics per robot that is O(robots^2) work per tick in a
// process that hosts thousands of robots and the simulator. The global topics (/flock/...) stay
// ROS topics: they are one publication per process whatever the swarm's size.
#ifndef SWARM_TRANSPORT_ROS_DIRECT_LINK_H_
#define SWARM_TRANSPORT_ROS_DIRECT_LINK_H_

#include <geometry_msgs/Twist.h>
#include <ros/callback_queue_interface.h>

#include <cstdint>
#include <functional>
#include <mutex>
#include <utility>
#include <vector>

#include "swarm_transport/Neighbors.h"
#include "swarm_transport/Tick_Answer.h"

namespace swarm_transport {

// Where a robot with a direct link sends what it would publish on robot_<id>/cmd_vel and, in
// lock-step, robot_<id>/answer. The content is exactly what it would publish.
class RobotOutlet {
 public:
  virtual ~RobotOutlet() = default;
  // Robot `id`'s command of this tick (also its last zero command when it stops).
  virtual void SendCommand(std::uint16_t id, const geometry_msgs::Twist& command) = 0;
  // Lock-step: robot `id`'s answer to a tick (its command and its mission messages).
  virtual void SendAnswer(std::uint16_t id, const Tick_Answer& answer) = 0;
};

// The simulator's side: the robots of its own process that take their radio rounds directly.
// Every method is called from the simulator's thread.
class DirectRobots {
 public:
  virtual ~DirectRobots() = default;
  // True when robot `id` is hosted here and linked directly (it neither subscribes
  // robot_<id>/neighbors nor publishes robot_<id>/cmd_vel or answer).
  virtual bool Hosts(std::uint16_t id) const = 0;
  // Hands robot `id` its radio round. It must not run the robot's tick before returning: the
  // simulator is in the middle of its round (the robot runs on its own callback queue).
  virtual void Deliver(std::uint16_t id, const Neighbors::ConstPtr& round) = 0;
  // Every round of this radio round is delivered: a host that collects them (real time) hands
  // them to its robots now, with one wake-up per thread instead of one per robot.
  virtual void EndRound() {}
  // Lock-step: runs the callbacks the hosted robots have pending, in the calling (the
  // simulator's) thread. Real time: robots run on their own threads and this does nothing.
  virtual void SpinRobots() = 0;
  // A robot spawned while the swarm runs: the process starts a robot for it and links it
  // directly (true), or leaves it to a process of its own (false). Before the simulator
  // connects the robot's links.
  virtual bool Adopt(std::uint16_t /*id*/) { return false; }
  // Robot `id` left the world (killed or deleted): the process stops and removes its robot.
  virtual void Release(std::uint16_t /*id*/) {}
  // False: the simulator offers no robot_<id>/teleport_* services for these robots.
  virtual bool RobotServices() const { return true; }
};

// Commands of directly linked robots sent from threads other than the simulator's (a real-time
// robot's worker), in arrival order, for the simulator's loop: one mutex, no callback-queue
// entry per robot and tick.
class CommandMailbox {
 public:
  void Post(std::uint16_t id, const geometry_msgs::Twist& command) {
    std::lock_guard<std::mutex> lock(mutex_);
    posted_.emplace_back(id, command);
  }
  // Calls take(id, command) for every command posted since the last call, in order.
  template <typename F>
  void TakeAll(F take) {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (posted_.empty()) return;
      taken_.swap(posted_);
    }
    for (const auto& command : taken_) take(command.first, command.second);
    taken_.clear();  // keeps its memory: no allocation once warm
  }

 private:
  std::mutex mutex_;
  std::vector<std::pair<std::uint16_t, geometry_msgs::Twist>> posted_;
  std::vector<std::pair<std::uint16_t, geometry_msgs::Twist>> taken_;
};

// A callback queue entry that runs a function: how a round reaches a robot's queue, or a
// command the simulator's command queue, from another thread.
class QueuedCall : public ros::CallbackInterface {
 public:
  explicit QueuedCall(std::function<void()> call) : call_(std::move(call)) {}
  CallResult call() override {
    call_();
    return Success;
  }

 private:
  std::function<void()> call_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_DIRECT_LINK_H_
