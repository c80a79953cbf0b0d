// One robot of the swarm: ~id, the shared /swarm configuration, a tick per perception.
#include <ros/ros.h>

#include "swarm_transport/ros/master_watch.h"
#include "swarm_transport/ros/robot_node.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "robot");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  swarm_transport::RobotNode node(nh, private_nh);
  if (!node.Initialize()) return 1;
  swarm_transport::MasterWatch watch;  // a master restart stops the node
  ros::spin();
  node.Shutdown();
  return watch.ExitCode(0);
}
