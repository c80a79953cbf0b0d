#include "swarm_transport/ros/master_watch.h"

#include <ros/master.h>
#include <ros/ros.h>
#include <ros/xmlrpc_manager.h>

#include <chrono>
#include <string>

namespace swarm_transport {
namespace {

// The master's record of this node: its XML-RPC URI, or "" when it does not know it.
std::string RegisteredUri() {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = ros::this_node::getName();
  if (!ros::master::execute("lookupNode", args, result, payload, false)) return "";
  return payload.getType() == XmlRpc::XmlRpcValue::TypeString ? std::string(payload) : "";
}

}  // namespace

MasterWatch::MasterWatch(double period_s) : thread_(&MasterWatch::Run, this, period_s) {}

MasterWatch::~MasterWatch() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

void MasterWatch::Run(double period_s) {
  const auto period = std::chrono::duration<double>(period_s);
  bool was_down = false;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, period);
    if (stop_ || !ros::ok()) break;
    lock.unlock();
    const bool up = ros::master::check();
    if (!up && !was_down) {
      ROS_WARN("%s: the ROS master at %s is unreachable; going on without it",
               ros::this_node::getName().c_str(), ros::master::getURI().c_str());
      was_down = true;
    } else if (up && was_down) {
      was_down = false;
      const std::string uri = RegisteredUri();
      if (uri != ros::XMLRPCManager::instance()->getServerURI()) {
        ROS_FATAL(
            "%s: the ROS master at %s restarted and does not know this node (its topics, "
            "services and parameters are gone there); stopping - launch the swarm again",
            ros::this_node::getName().c_str(), ros::master::getURI().c_str());
        restarted_ = true;
        ros::requestShutdown();
        return;
      }
      ROS_INFO("%s: the ROS master is reachable again and still knows this node",
               ros::this_node::getName().c_str());
    }
    lock.lock();
  }
}

}  // namespace swarm_transport
