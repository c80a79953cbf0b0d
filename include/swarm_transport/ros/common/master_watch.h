// Watches the ROS master from a thread of its own (issue 11). ROS 1 nodes do not register
// again after a master restart: the new master knows none of them, and their topics, services
// and parameters are gone for anyone who asks it. A node with a MasterWatch tells the new
// master by its process id (getPid; each call to the master ends after 2 s, so that a master
// that accepts a connection but never answers does not hold the watch), notices within two
// periods, says so in one line and stops (ros::requestShutdown), so that it does not run on
// unreachable; restarted() tells its main to exit non-zero (roslaunch respawn="true" restarts a
// node, but a swarm needs its /swarm parameters loaded again: relaunch it). A master that was
// only unreachable for a while (it still knows this node) changes nothing.
#ifndef SWARM_TRANSPORT_ROS_MASTER_WATCH_H_
#define SWARM_TRANSPORT_ROS_MASTER_WATCH_H_

#include <atomic>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>

namespace swarm_transport {

class MasterWatch {
 public:
  // Right after ros::init and the node's first NodeHandle (ros::start registers the node with
  // the master), before the node's set-up (a restart during a set-up that waits for the master
  // is caught too); checks every `period_s` of wall time.
  explicit MasterWatch(double period_s = 5.0);
  ~MasterWatch();
  MasterWatch(const MasterWatch&) = delete;
  MasterWatch& operator=(const MasterWatch&) = delete;

  // The master restarted and lost this node: it was asked to stop.
  bool restarted() const { return restarted_; }

  // What one look at the master found.
  enum class Look { kUnreachable, kUp, kReachableAgain, kRestarted };
  // One look: `*known_pid` is the master's pid as last known (0: it never answered; set at the
  // first answer), `pid` its pid now (0: no answer in time), `was_down` whether the last look
  // found it unreachable, `knows` asks it whether it knows this node (nullopt: no answer; asked
  // only after it was down or at the first answer). A master with another pid, or one that has
  // lost this node (which registered with a master before the watch began), restarted.
  static Look Judge(int* known_pid, int pid, bool was_down,
                    const std::function<std::optional<bool>()>& knows);
  // The process exit code for main: 3 after a restart, else `otherwise`.
  int ExitCode(int otherwise) const { return restarted_ ? 3 : otherwise; }

 private:
  void Run(double period_s);

  std::atomic<bool> restarted_{false};
  int master_pid_;  // the master's pid (0: no answer yet; Judge sets it at the first); Run's own
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_MASTER_WATCH_H_
