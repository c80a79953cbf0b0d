// A real-time robot's own tick: it acts once per radio round, and stands when rounds stop.
#include <geometry_msgs/Twist.h>

#include "swarm_transport/ros/robot/robot_node.h"

namespace swarm_transport {

void RobotNode::TimerTick() {
  if (!perception_) return;
  // No round for as long as its peers would take to count a robot lost: it would act on where
  // it and they were then, sending the same relative turn again and again. It stands until
  // rounds return, as a robot on hardware without poses does.
  core::PoseWatch::Change change = core::PoseWatch::Change::kNone;
  const double now_s = ros::WallTime::now().toSec();
  const bool fresh = round_watch_.Check(now_s, &change);
  if (change == core::PoseWatch::Change::kStale) {
    ROS_WARN(
        "robot %u: no radio round for %.2f s (/swarm/lost_after_s %.2f): it stands until "
        "rounds return",
        id_, round_watch_.AgeS(now_s), config_.lost_after_s);
  } else if (change == core::PoseWatch::Change::kFresh) {
    ROS_INFO("robot %u: radio rounds are back: it moves again", id_);
  }
  if (!fresh) {
    transport_->SendCommand(geometry_msgs::Twist());
    echo_.Forget();
    return;
  }
  // One move per round (SPEC 4: its prediction must match what the simulator executes). A
  // second move from the same round would plan from a pose its last command already left: the
  // simulator turns at once on receipt, so the same relative turn would be turned twice, and a
  // robot whose rounds come late (a starved simulator or robot) turns on and on. It waits; its
  // last command drives for one tick and ends, so it stands until the next round.
  if (round_acted_) {
    ++round_waits_;
    return;
  }
  round_acted_ = true;
  Tick();
}

}  // namespace swarm_transport
