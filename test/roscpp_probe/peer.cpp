// scripts/roscpp_probe's peer: publishes /probe/t0 .. /probe/t<K-1> at 10 Hz (or, with
// "subscriber" as its second argument, subscribes to them) until it is killed; started again
// under the same node name, as a respawned robot or a restarted dispatcher is.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

namespace {
void Ignore(const std_msgs::String::ConstPtr& /*msg*/) {}
}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "probe_peer");
  const int topics = argc > 1 ? std::atoi(argv[1]) : 1;
  const bool subscriber = argc > 2 && std::strcmp(argv[2], "subscriber") == 0;
  ros::NodeHandle nh;
  std::vector<ros::Publisher> pubs;
  std::vector<ros::Subscriber> subs;
  for (int k = 0; k < topics; ++k) {
    const std::string topic = "/probe/t" + std::to_string(k);
    if (subscriber) {
      subs.push_back(nh.subscribe(topic, 10, &Ignore));
    } else {
      pubs.push_back(nh.advertise<std_msgs::String>(topic, 10));
    }
  }
  if (subscriber) {
    ros::spin();
    return 0;
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
