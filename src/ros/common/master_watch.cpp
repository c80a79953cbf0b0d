#include "swarm_transport/ros/common/master_watch.h"

#include <ros/master.h>
#include <ros/ros.h>
#include <ros/xmlrpc_manager.h>
#include <xmlrpcpp/XmlRpcClient.h>

#include <chrono>
#include <optional>
#include <string>

namespace swarm_transport {
namespace {

// Longest wait for one answer of the master (wall s). roscpp's own calls to the master
// (ros::master::execute) wait for as long as the connection stays open: a master that accepted
// the connection but never answers (one stopped, hung, or just starting on the port) would
// hold the watch for good, and a restart would go unnoticed.
constexpr double kCallTimeoutS = 2.0;

// An XML-RPC client of the master whose calls end after kCallTimeoutS. The watch's own (its
// thread only): roscpp's clients are shared by its threads.
class MasterClient : public XmlRpc::XmlRpcClient {
 public:
  MasterClient() : XmlRpcClient(ros::master::getHost().c_str(), ros::master::getPort(), "/") {}

  // The master's ROS API reply [code, status, value] (code 1: done; -1, 0: its "no"), or
  // nullopt when it did not answer in time (or not with such a reply).
  std::optional<XmlRpc::XmlRpcValue> Call(const char* method, const XmlRpc::XmlRpcValue& args) {
    if (!executeNonBlock(method, args)) {
      close();
      return std::nullopt;
    }
    // Returns when the reply is in, the connection failed, or at the deadline.
    _disp.work(kCallTimeoutS);
    XmlRpc::XmlRpcValue reply;
    if (_connectionState != IDLE || !executeCheckDone(reply) || isFault()) {
      close();
      return std::nullopt;
    }
    if (reply.getType() != XmlRpc::XmlRpcValue::TypeArray || reply.size() != 3 ||
        reply[0].getType() != XmlRpc::XmlRpcValue::TypeInt) {
      return std::nullopt;
    }
    return reply;
  }
};

// Whether the master's record of this node is this process's XML-RPC server (nullopt: no
// answer in time). A master that does not know the node answers with an error code.
std::optional<bool> KnowsThisNode(MasterClient* master) {
  XmlRpc::XmlRpcValue args;
  args[0] = ros::this_node::getName();
  args[1] = ros::this_node::getName();
  std::optional<XmlRpc::XmlRpcValue> reply = master->Call("lookupNode", args);
  if (!reply) return std::nullopt;
  XmlRpc::XmlRpcValue& uri = (*reply)[2];
  return int((*reply)[0]) == 1 && uri.getType() == XmlRpc::XmlRpcValue::TypeString &&
         std::string(uri) == ros::XMLRPCManager::instance()->getServerURI();
}

// The master's process id, or 0 when it does not answer in time. A master started again on the
// same port is another process: its pid tells it apart even when this node never saw it down.
int MasterPid(MasterClient* master) {
  XmlRpc::XmlRpcValue args;
  args[0] = ros::this_node::getName();
  std::optional<XmlRpc::XmlRpcValue> reply = master->Call("getPid", args);
  if (!reply || int((*reply)[0]) != 1) return 0;
  XmlRpc::XmlRpcValue& pid = (*reply)[2];
  return pid.getType() == XmlRpc::XmlRpcValue::TypeInt ? int(pid) : 0;
}

// The master's pid as the watch begins (a client of its own: the watch thread has another).
int InitialMasterPid() {
  MasterClient master;
  return MasterPid(&master);
}

}  // namespace

MasterWatch::MasterWatch(double period_s)
    : master_pid_(InitialMasterPid()), thread_(&MasterWatch::Run, this, period_s) {}

MasterWatch::~MasterWatch() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  if (thread_.joinable()) thread_.join();
}

MasterWatch::Look MasterWatch::Judge(int* known_pid, int pid, bool was_down,
                                     const std::function<std::optional<bool>()>& knows) {
  if (pid == 0) return Look::kUnreachable;
  const bool first = *known_pid == 0;
  if (!first && pid != *known_pid) return Look::kRestarted;
  if (first || was_down) {
    // The first answer (none when the watch began: the master may have gone and come back
    // since the node registered) or the first after it was down: it must still know this node.
    const std::optional<bool> known = knows();
    if (!known) return Look::kUnreachable;  // asked again at the next look
    if (!*known) return Look::kRestarted;
    *known_pid = pid;
  }
  return was_down ? Look::kReachableAgain : Look::kUp;
}

void MasterWatch::Run(double period_s) {
  const auto period = std::chrono::duration<double>(period_s);
  bool was_down = false;
  MasterClient master;
  std::unique_lock<std::mutex> lock(mutex_);
  while (!stop_) {
    wake_.wait_for(lock, period);
    if (stop_ || !ros::ok()) break;
    lock.unlock();
    const Look look = Judge(&master_pid_, MasterPid(&master), was_down,
                            [&master] { return KnowsThisNode(&master); });
    switch (look) {
      case Look::kUnreachable:
        if (!was_down) {
          ROS_WARN("%s: the ROS master at %s is unreachable; going on without it",
                   ros::this_node::getName().c_str(), ros::master::getURI().c_str());
        }
        was_down = true;
        break;
      case Look::kRestarted:
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
      case Look::kReachableAgain:
        was_down = false;
        ROS_INFO("%s: the ROS master is reachable again and still knows this node",
                 ros::this_node::getName().c_str());
        break;
      case Look::kUp:
        break;
    }
    lock.lock();
  }
}

}  // namespace swarm_transport
