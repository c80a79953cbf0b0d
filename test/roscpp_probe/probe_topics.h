// What scripts/roscpp_probe's two nodes share: /probe/t0 .. /probe/t<K-1> (std_msgs/String),
// taken in and dropped, or published at 10 Hz until shutdown.
#ifndef SWARM_TRANSPORT_TEST_ROSCPP_PROBE_PROBE_TOPICS_H
#define SWARM_TRANSPORT_TEST_ROSCPP_PROBE_PROBE_TOPICS_H

#include <ros/ros.h>
#include <std_msgs/String.h>

#include <string>
#include <vector>

namespace probe {

inline void Ignore(const std_msgs::String::ConstPtr& /*msg*/) {}

// Subscribes to (or, with `publish`, advertises) the K topics, then spins (or publishes at
// 10 Hz) until the node is shut down.
inline int Run(int topics, bool publish) {
  ros::NodeHandle nh;
  std::vector<ros::Subscriber> subs;
  std::vector<ros::Publisher> pubs;
  for (int k = 0; k < topics; ++k) {
    const std::string topic = "/probe/t" + std::to_string(k);
    if (publish) {
      pubs.push_back(nh.advertise<std_msgs::String>(topic, 10));
    } else {
      subs.push_back(nh.subscribe(topic, 10, &Ignore));
    }
  }
  if (!publish) {
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

}  // namespace probe

#endif  // SWARM_TRANSPORT_TEST_ROSCPP_PROBE_PROBE_TOPICS_H
