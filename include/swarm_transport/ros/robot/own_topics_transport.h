// A robot process's transport (robot.launch, deploy:=process): every topic its own - its
// robot_<id>/neighbors in, robot_<id>/cmd_vel (real time) or robot_<id>/answer (lock-step)
// out, the robot list and, in real time, the mission topics. In real time it also runs the
// robot's own tick loop (tick_loop.h): its ticks in roscpp's poll thread on its own timeline,
// its other callbacks in the spinning thread, both under one lock.
#ifndef SWARM_TRANSPORT_ROS_OWN_TOPICS_TRANSPORT_H_
#define SWARM_TRANSPORT_ROS_OWN_TOPICS_TRANSPORT_H_

#include <ros/ros.h>

#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "swarm_transport/ros/common/mission_topics.h"
#include "swarm_transport/ros/robot/robot_transport.h"
#include "swarm_transport/ros/robot/tick_loop.h"

namespace swarm_transport {

class OwnTopicsTransport : public RobotTransport {
 public:
  explicit OwnTopicsTransport(core::Clock clock) : clock_(clock) {}
  void Prepare(ros::NodeHandle* nh, ros::NodeHandle* private_nh) override;
  void Connect(ros::NodeHandle nh, const TransportOptions& link, RobotInbox* robot) override;
  void Disconnect() override;
  void SendAnswer(const Tick_Answer& answer) override { answer_pub_.publish(answer); }
  void SendCommand(const geometry_msgs::Twist& command) override;
  void SendStats(const std::string& line) override;
  bool Spin(double tick_period_s) override;
  void Stop() override { ticker_.Stop(); }
  bool OwnProcess() const override { return true; }
  bool SimulatorTurnsOnReceipt() const override { return true; }
  int CommandListeners() const override {
    return cmd_pub_ ? static_cast<int>(cmd_pub_.getNumSubscribers()) : -1;
  }

 private:
  bool realtime() const { return clock_ == core::Clock::kRealtime; }
  // Its tick is due (the poll thread): takes in the rounds that arrived and ticks.
  void OnTickDue();
  // Real time: it subscribes its neighbors (and so is heard on the radio, and moves) only once
  // the dispatcher's topics are connected, at most kDispatcherWaitS after its start. A robot
  // heard before it can get orders missed a mission that named it (a process started again
  // while the dispatcher sent it), and its members, hearing it, waited for it for good; a
  // quiet one is lost to them after lost_after_s, and the mission goes on without it.
  void AwaitDispatcher(ros::NodeHandle nh);
  void SubscribeNeighbors(ros::NodeHandle nh);

  const core::Clock clock_;
  RobotInbox* robot_ = nullptr;
  std::uint16_t id_ = 0;
  // Real time: declared before every subscriber, so that they outlive them. Its handles'
  // callbacks run on the spinning thread under mutex_ (locked_queue_), its rounds' callback
  // where they arrive (inline_queue_: into the mailbox, taken at its next tick).
  std::mutex mutex_;
  std::unique_ptr<LockedCallbackQueue> locked_queue_;
  InlineCallbackQueue inline_queue_;
  RoundMailbox mailbox_;
  std::vector<RoundMailbox::Arrived> arrived_;
  PollThreadTicker ticker_;
  ros::Subscriber neighbors_sub_;
  ros::WallTimer dispatcher_wait_;  // real time, until AwaitDispatcher is done
  ros::Subscriber robots_sub_;
  MissionTopics mission_topics_;  // real time
  ros::Publisher cmd_pub_;        // real time
  ros::Publisher answer_pub_;     // lock-step
  ros::Publisher stats_pub_;      // diagnostics
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_OWN_TOPICS_TRANSPORT_H_
