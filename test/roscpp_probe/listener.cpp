// scripts/roscpp_probe's plain roscpp node, long-lived: subscribes to /probe/t0 .. /probe/t<K-1>
// (std_msgs/String), or with "publisher" as its second argument publishes them at 10 Hz, and
// does nothing else - no code of swarm_transport. Its heap is what roscpp alone holds while
// the peer on the other end of those topics is killed and started again.
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
  ros::init(argc, argv, "probe_listener");
  const int topics = argc > 1 ? std::atoi(argv[1]) : 1;
  const bool publisher = argc > 2 && std::strcmp(argv[2], "publisher") == 0;
  ros::NodeHandle nh;
  std::vector<ros::Subscriber> subs;
  std::vector<ros::Publisher> pubs;
  for (int k = 0; k < topics; ++k) {
    const std::string topic = "/probe/t" + std::to_string(k);
    if (publisher) {
      pubs.push_back(nh.advertise<std_msgs::String>(topic, 10));
    } else {
      subs.push_back(nh.subscribe(topic, 10, &Ignore));
    }
  }
  if (!publisher) {
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
