// The mission dispatcher: accepts, validates, publishes and tracks missions; signals loading.
#include <ros/ros.h>

#include "swarm_transport/ros/master_watch.h"
#include "swarm_transport/ros/mission_dispatcher.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "mission_dispatcher");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  swarm_transport::MissionDispatcher dispatcher(nh, private_nh);
  if (!dispatcher.Initialize()) return 1;
  swarm_transport::MasterWatch watch;  // a master restart stops the node
  ros::spin();
  dispatcher.Shutdown();
  return watch.ExitCode(0);
}
