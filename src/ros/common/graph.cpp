#include "swarm_transport/ros/common/graph.h"

#include <ros/master.h>

namespace swarm_transport {
namespace {

std::uint32_t CountOf(const std::map<std::string, std::uint32_t>& counts,
                      const std::string& topic) {
  const auto it = counts.find(topic);
  return it == counts.end() ? 0 : it->second;
}

void Read(XmlRpc::XmlRpcValue& list, std::map<std::string, std::uint32_t>* out) {
  out->clear();
  for (int i = 0; i < list.size(); ++i) {
    (*out)[static_cast<std::string>(list[i][0])] = static_cast<std::uint32_t>(list[i][1].size());
  }
}

}  // namespace

std::uint32_t TopicNodeCounts::Publishers(const std::string& topic) const {
  return CountOf(publishers, topic);
}

std::uint32_t TopicNodeCounts::Subscribers(const std::string& topic) const {
  return CountOf(subscribers, topic);
}

bool TopicNodeCounts::AllConnected(const ros::Publisher& pub) const {
  return pub.getNumSubscribers() >= Subscribers(pub.getTopic());
}

bool TopicNodeCounts::AllConnected(const ros::Subscriber& sub) const {
  return sub.getNumPublishers() >= Publishers(sub.getTopic());
}

bool QueryTopicNodeCounts(TopicNodeCounts* out, bool wait_for_master) {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", request, response, payload, wait_for_master)) {
    return false;
  }
  Read(payload[0], &out->publishers);
  Read(payload[1], &out->subscribers);
  return true;
}

bool QuerySubscriberNodes(const std::string& topic, std::vector<std::string>* nodes) {
  XmlRpc::XmlRpcValue request, response, payload;
  request[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", request, response, payload, false)) return false;
  nodes->clear();
  XmlRpc::XmlRpcValue& subscribed = payload[1];
  for (int i = 0; i < subscribed.size(); ++i) {
    if (static_cast<std::string>(subscribed[i][0]) != topic) continue;
    for (int j = 0; j < subscribed[i][1].size(); ++j) {
      nodes->push_back(static_cast<std::string>(subscribed[i][1][j]));
    }
  }
  return true;
}

bool AwaitSubscribers(const ros::Publisher& pub, double wait_s, double poll_s) {
  const ros::WallTime until = ros::WallTime::now() + ros::WallDuration(wait_s);
  while (ros::ok()) {
    TopicNodeCounts graph;
    if (!QueryTopicNodeCounts(&graph) || graph.AllConnected(pub)) return true;
    if (ros::WallTime::now() >= until) return false;
    ros::WallDuration(poll_s).sleep();
  }
  return true;
}

}  // namespace swarm_transport
