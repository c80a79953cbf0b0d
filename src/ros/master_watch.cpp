#include "swarm_transport/ros/master_watch.h"

#include <ros/master.h>
#include <ros/ros.h>
#include <ros/xmlrpc_manager.h>

#include <chrono>
#include <string>

namespace swarm_transport {
namespace {

// Whether the master's record of this node is this process's XML-RPC server.
bool KnowsThisNode() {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = ros::this_node::getName();
  if (!ros::master::execute("lookupNode", args, result, payload, false)) return false;
  return payload.getType() == XmlRpc::XmlRpcValue::TypeString &&
         std::string(payload) == ros::XMLRPCManager::instance()->getServerURI();
}

// The master's process id, or 0 when it does not answer. A master started again on the same
// port is another process: its pid tells it apart even when this node never saw it down.
int MasterPid() {
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getPid", args, result, payload, false)) return 0;
  return payload.getType() == XmlRpc::XmlRpcValue::TypeInt ? int(payload) : 0;
}

}  // namespace

MasterWatch::MasterWatch(double period_s)
    : master_pid_(MasterPid()), thread_(&MasterWatch::Run, this, period_s) {}

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
    const int pid = MasterPid();
    if (pid == 0) {
      if (!was_down) {
        ROS_WARN("%s: the ROS master at %s is unreachable; going on without it",
                 ros::this_node::getName().c_str(), ros::master::getURI().c_str());
      }
      was_down = true;
    } else if (master_pid_ == 0) {
      master_pid_ = pid;  // first contact: unreachable when the node started
      was_down = false;
    } else if (pid != master_pid_ || (was_down && !KnowsThisNode())) {
      // Another master process: it knows nothing this node registered before it came up,
      // even if the node's set-up went on registering with it (a set-up that waited for the
      // master) - its topics, services and parameters are incomplete there.
      ROS_FATAL(
          "%s: the ROS master at %s restarted and does not know this node (its topics, "
          "services and parameters are gone there); stopping - launch the swarm again",
          ros::this_node::getName().c_str(), ros::master::getURI().c_str());
      restarted_ = true;
      ros::requestShutdown();
      return;
    } else if (was_down) {
      was_down = false;
      ROS_INFO("%s: the ROS master is reachable again and still knows this node",
               ros::this_node::getName().c_str());
    }
    lock.lock();
  }
}

}  // namespace swarm_transport
