#include "swarm_transport/ros/robot/host_transport.h"

#include "swarm_transport/ros/common/names.h"

namespace swarm_transport {

void HostTransport::Connect(ros::NodeHandle nh, const TransportOptions& link, RobotInbox* robot) {
  if (link.clock == core::Clock::kLockstep) {
    answer_pub_ = nh.advertise<Tick_Answer>(names::kAnswer, 2);
  } else {
    cmd_pub_ = nh.advertise<geometry_msgs::Twist>(names::kCmdVel, 2);
  }
  // One message per tick (a robot is never more than one tick behind); tcpNoDelay: a tick's
  // perception is one small message, Nagle would add ~40 ms per tick.
  neighbors_sub_ = nh.subscribe<Neighbors>(
      names::kNeighbors, 2,
      boost::function<void(const Neighbors::ConstPtr&)>([robot](const Neighbors::ConstPtr& msg) {
        robot->TakeRound(msg, ros::WallTime::now().toSec());
      }),
      ros::VoidConstPtr(), ros::TransportHints().tcpNoDelay());
}

void HostTransport::SendCommand(const geometry_msgs::Twist& command) {
  if (cmd_pub_) cmd_pub_.publish(command);
}

}  // namespace swarm_transport
