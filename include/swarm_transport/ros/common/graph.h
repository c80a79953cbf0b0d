// What the ROS master knows of the graph: how many nodes publish and subscribe each topic.
// A link counts at the master once the node registered, and at a publisher or subscriber
// once the connection is made; comparing the two tells whether every registered node is
// connected (a latched message delivered, a status not lost).
#ifndef SWARM_TRANSPORT_ROS_GRAPH_H_
#define SWARM_TRANSPORT_ROS_GRAPH_H_

#include <ros/ros.h>

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace swarm_transport {

struct TopicNodeCounts {
  std::map<std::string, std::uint32_t> publishers;   // topic -> publishing nodes
  std::map<std::string, std::uint32_t> subscribers;  // topic -> subscribing nodes
  std::uint32_t Publishers(const std::string& topic) const;
  std::uint32_t Subscribers(const std::string& topic) const;
  // Every node registered as a subscriber of the publisher's topic is connected to it.
  bool AllConnected(const ros::Publisher& pub) const;
  // Every node registered as a publisher of the subscriber's topic is connected to it.
  bool AllConnected(const ros::Subscriber& sub) const;
};

// Asks the master (getSystemState); false when it cannot be asked. `wait_for_master`: block
// until the master answers.
bool QueryTopicNodeCounts(TopicNodeCounts* out, bool wait_for_master = false);

// The nodes the master lists as subscribers of `topic` (getSystemState); false when it cannot
// be asked.
bool QuerySubscriberNodes(const std::string& topic, std::vector<std::string>* nodes);

// Waits (wall time, polling the master every poll_s) at most wait_s until every node registered
// as a subscriber of pub's topic is connected to it: a message published before a connection is
// made never reaches that node. Connections are made by roscpp's own threads, so a callback may
// wait here. False after wait_s (or when the master cannot be asked at all: then true).
bool AwaitSubscribers(const ros::Publisher& pub, double wait_s, double poll_s = 0.005);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_GRAPH_H_
