// The mission dispatcher: accepts, validates, publishes and tracks missions; signals loading.
#include <ros/ros.h>

#include "swarm_transport/ros/common/master_watch.h"
#include "swarm_transport/ros/dispatcher/mission_dispatcher.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "mission_dispatcher");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  // Before the set-up: a master restart stops the node, even one during its set-up.
  swarm_transport::MasterWatch watch;
  swarm_transport::MissionDispatcher dispatcher(nh, private_nh);
  if (!dispatcher.Initialize()) return watch.ExitCode(1);
  ros::spin();
  dispatcher.Shutdown();
  return watch.ExitCode(0);
}
