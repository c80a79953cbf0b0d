// scripts/roscpp_probe's plain roscpp node: subscribes to /probe/t0 .. /probe/t<K-1>
// (std_msgs/String) and does nothing else - no code of swarm_transport. Its heap is what
// roscpp alone holds while the publisher of those topics is killed and started again.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <cstdlib>
#include <string>
#include <vector>

namespace {
void Ignore(const std_msgs::String::ConstPtr& /*msg*/) {}
}  // namespace

int main(int argc, char** argv) {
  ros::init(argc, argv, "probe_listener");
  const int topics = argc > 1 ? std::atoi(argv[1]) : 1;
  ros::NodeHandle nh;
  std::vector<ros::Subscriber> subs;
  for (int k = 0; k < topics; ++k) {
    subs.push_back(nh.subscribe("/probe/t" + std::to_string(k), 10, &Ignore));
  }
  ros::spin();
  return 0;
}
