// scripts/roscpp_probe's peer: publishes /probe/t0 .. /probe/t<K-1> at 10 Hz until it is
// killed; started again under the same node name, as a respawned robot or a restarted
// dispatcher is.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  ros::init(argc, argv, "probe_peer");
  const int topics = argc > 1 ? std::atoi(argv[1]) : 1;
  ros::NodeHandle nh;
  std::vector<ros::Publisher> pubs;
  for (int k = 0; k < topics; ++k) {
    pubs.push_back(nh.advertise<std_msgs::String>("/probe/t" + std::to_string(k), 10));
  }
  std_msgs::String msg;
  msg.data = "probe";
  ros::Rate rate(10.0);
  while (ros::ok()) {
    for (ros::Publisher& pub : pubs) pub.publish(msg);
    rate.sleep();
  }
  return 0;
}
