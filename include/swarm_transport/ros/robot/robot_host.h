// Many robots in one process: RobotNode instances that behave as with a process per robot, each
// over the transport its deployment needs (host_transport.h).
#ifndef SWARM_TRANSPORT_ROS_ROBOT_HOST_H_
#define SWARM_TRANSPORT_ROS_ROBOT_HOST_H_

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <boost/container/flat_map.hpp>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/core/modes.h"
#include "swarm_transport/ros/common/diagnostics.h"
#include "swarm_transport/ros/common/direct_link.h"
#include "swarm_transport/ros/common/mission_topics.h"
#include "swarm_transport/ros/robot/host_transport.h"
#include "swarm_transport/ros/robot/host_worker.h"
#include "swarm_transport/ros/robot/robot_node.h"

namespace swarm_transport {

// Private parameters of the host (the robots' behaviour comes from /swarm as usual).
struct RobotHostOptions {
  int from = 0;                                // ~from: first robot id, [0, 65535]
  int to = 0;                                  // ~to: one past the last id, (from, 65536]
  core::Clock clock = core::Clock::kRealtime;  // ~clock: realtime | lockstep, every robot
  core::Comm comm = core::Comm::kLocal;        // ~comm: local | broadcast, every robot
  bool diagnostics = false;  // ~diagnostics: every robot publishes /flock/robot_stats
  // ~threads: callback threads, [1, 64]. Robot k is served by thread k % threads only, so one
  // robot's callbacks never run concurrently; 1 (default) also keeps the order of callbacks
  // across robots fixed, which lock-step determinism does not need but debugging likes.
  int threads = 1;
  // ~deploy: host (default) | host_sim, swarm.launch's deploy. host_sim also runs the simulator
  // in this process (its private parameters under ~simulator/, as under /simulator/ for the
  // simulator node; its ~clock must be ours). The simulator and the hosted robots are then
  // linked directly (direct_link.h): no robot_<id>/neighbors, cmd_vel or answer topics, and by
  // default no robot_<id>/pose (~simulator/pose_topics). Lock-step runs the robots in the
  // simulator's thread.
  core::Deploy deploy = core::Deploy::kHost;
  bool RunsSimulator() const { return deploy == core::Deploy::kHostSim; }
  // ~adopt: the swarm changes size while it runs (issue 11): a robot spawned later (/spawn,
  // New_Robot) gets a robot of this host, and a robot of this host that leaves the world
  // (/kill, Delete_Robot) is removed. With deploy host_sim the simulator tells the host;
  // without, the host runs every robot /flock/robots lists. false: robots beyond [from, to)
  // need processes of their own (a host beside robot processes).
  bool adopt = true;
  // ~robot_services: every robot offers its services as a process of its own would
  // (robot_<id>/robot/describe and state; with host_sim the simulator's
  // robot_<id>/teleport_absolute and teleport_relative). false: none of them. Each one is a master
  // registration and, in roscpp, a linear search over all of the process's services: at 10,000
  // robots that was most of a start-up of 514 s. Default true.
  bool robot_services = true;
  std::string Validate() const;
};

class Simulator;

// The in-process twin of robots.launch [issue 5]: robot <id> gets the handles
// NodeHandle("robot_<id>") and NodeHandle("robot_<id>/robot"), so its topics, its ~describe
// service and its parameters resolve exactly as for the node /robot_<id>/robot; global topics
// are shared, and roscpp delivers messages between the hosted robots without serialising. The
// swarm-wide topics are subscribed once for all the robots (SubscribeSharedTopics).
// Real time: a worker thread per queue (HostWorker) ticks its robots from one heap of due times
// instead of a wall timer per robot (roscpp's timer manager re-sorts all of a process's timers,
// with a linear search per comparison, at every expiry), and runs their roscpp callbacks.
// With ~deploy host_sim the host is the simulator's DirectRobots: in real time it hands each
// worker its robots' rounds once per radio round (EndRound); in lock-step it delivers each round
// on the robot's callback queue and runs those queues from the simulator's thread (no spinner
// threads: no hand-offs, and the order of callbacks is fixed).
class RobotHost : public DirectRobots {
 public:
  RobotHost(ros::NodeHandle nh, ros::NodeHandle private_nh);
  ~RobotHost();
  // Loads and validates parameters, starts every robot. False (after one ROS_FATAL) on bad
  // parameters or when a robot fails to start.
  bool Initialize();
  // Runs the robots until ROS shuts down.
  void Spin();
  // Stops ticking; every robot sends a last zero velocity.
  void Shutdown();

  // DirectRobots (the simulator of this process calls these from its thread).
  bool Hosts(std::uint16_t id) const override;
  void Deliver(std::uint16_t id, const Neighbors::ConstPtr& round) override;
  void EndRound() override;
  void SpinRobots() override;
  bool Adopt(std::uint16_t id) override;
  void Release(std::uint16_t id) override;
  bool RobotServices() const override { return options_.robot_services; }

 private:
  struct Hosted {
    std::unique_ptr<RobotNode> node;
    ros::CallbackQueue* queue = nullptr;
    HostWorker* worker = nullptr;  // real time: the thread that runs it
    void* slot = nullptr;          // its place in that worker
  };
  // Starts robot `id` on the next queue (real time: it ticks from now on).
  bool StartRobot(std::uint16_t id);
  // Without the simulator here: robots join and leave as /flock/robots says (~adopt).
  void OnRobots(const Robot_Positions::ConstPtr& msg);
  // The swarm-wide topics (the robot list and, in real time, the mission topics), subscribed
  // once for every robot of the host on `nh`'s queue, the thread that also changes hosted_.
  void SubscribeSharedTopics(ros::NodeHandle nh);
  // Runs hear(robot) for every hosted robot, on the robot's queue.
  template <typename F>
  void FanOut(const F& hear);
  // No tick or callback runs after this returns.
  void StopCallbacks();

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  RobotHostOptions options_;
  std::unique_ptr<Simulator> simulator_;
  // Declared before the robots: their subscriptions refer to these queues.
  std::vector<std::unique_ptr<ros::CallbackQueue>> queues_;
  // ~diagnostics: declared before the robots, which add to it, and the workers, which flush it.
  std::unique_ptr<StatsBatch> stats_;
  // /swarm, read once for every robot (unset: each robot reads it and reports what is wrong).
  std::optional<SwarmConfig> swarm_;
  // The hosted robots by id. Changed only from one thread: the simulator's (~deploy host_sim,
  // which also calls Deliver) or the control queue's (/flock/robots).
  boost::container::flat_map<std::uint16_t, Hosted> hosted_;  // found for every round
  std::set<std::uint16_t> ids_;  // hosted or about to be (Hosts() before the robots start)
  std::size_t started_ = 0;      // robots started so far: robot k is served by queue k % n
  std::vector<std::unique_ptr<ros::AsyncSpinner>> spinners_;  // lock-step without simulator
  // Real time: one per queue. Declared after the queues (a worker waits on its queue) and the
  // robots (a worker runs them): members go in reverse order, so the workers stop first.
  std::vector<std::unique_ptr<HostWorker>> workers_;
  ros::CallbackQueue control_queue_;  // the host's own subscription (/flock/robots)
  std::unique_ptr<ros::AsyncSpinner> control_spinner_;
  ros::Subscriber robots_sub_;
  std::unique_ptr<NodeDiagnostics> diagnostics_;
  ros::WallTimer status_timer_;
  ros::Subscriber robots_shared_sub_;
  MissionTopics mission_topics_;
  // The latest /flock/robots (latched), for a robot that starts later.
  Robot_Positions::ConstPtr last_robots_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_ROBOT_HOST_H_
