// The mission dispatcher: accepts, validates, publishes and tracks missions; signals loading.
#include <ros/ros.h>

#include "swarm_transport/ros/mission_dispatcher.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "mission_dispatcher");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  swarm_transport::MissionDispatcher dispatcher(nh, private_nh);
  if (!dispatcher.Initialize()) return 1;
  ros::spin();
  dispatcher.Shutdown();
  return 0;
}
