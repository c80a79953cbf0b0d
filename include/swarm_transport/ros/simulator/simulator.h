// The simulator node: adapts the pure World2D to ROS, owns the clock and plays the radio.
#ifndef SWARM_TRANSPORT_ROS_SIMULATOR_H_
#define SWARM_TRANSPORT_ROS_SIMULATOR_H_

#include <geometry_msgs/Twist.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <csignal>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "swarm_transport/Neighbors.h"
#include "swarm_transport/TeleportAbsolute.h"
#include "swarm_transport/TeleportRelative.h"
#include "swarm_transport/Tick_Answer.h"
#include "swarm_transport/core/modes.h"
#include "swarm_transport/core/random.h"
#include "swarm_transport/ros/common/diagnostics.h"
#include "swarm_transport/ros/common/direct_link.h"
#include "swarm_transport/ros/common/wall_throttle.h"
#include "swarm_transport/ros/simulator/event_player.h"
#include "swarm_transport/ros/simulator/live_tuning.h"
#include "swarm_transport/ros/simulator/lockstep_hold.h"
#include "swarm_transport/ros/simulator/lockstep_session.h"
#include "swarm_transport/ros/simulator/mission_mirror.h"
#include "swarm_transport/ros/simulator/robot_links.h"
#include "swarm_transport/ros/simulator/robot_roster.h"
#include "swarm_transport/ros/simulator/simulator_params.h"
#include "swarm_transport/ros/simulator/visuals.h"
#include "swarm_transport/sim/lockstep_engine.h"
#include "swarm_transport/sim/radio.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {

// The turtlesim-like simulator [SPEC 7]: per-robot cmd_vel, pose, neighbors and teleport
// services, global spawn/kill/reset, /flock/world_poses, markers, tf, and in lock-step /clock.
// Single-threaded: every callback runs from Run()'s loop between world steps, so the world
// needs no lock and a tick's result never depends on thread scheduling.
// Robots hosted in the simulator's own process can be linked directly (AttachDirect): no
// neighbors / cmd_vel / answer topics for them; as a RobotOutlet the simulator takes their
// commands and answers into the same bookkeeping as the topics' (thread-safe).
// Lock-step is two messages per robot and tick: its Neighbors, its Tick_Answer. The answers'
// mission messages are relayed in the next tick's Neighbors, ordered by robot id, and published
// on the /flock/ mission topics for observers (the dispatcher, the recorder, rostopic).
class Simulator : public RobotOutlet {
 public:
  Simulator(ros::NodeHandle nh, ros::NodeHandle private_nh);
  // Before Initialize(): the robots of this process that take their rounds directly (must
  // outlive the simulator's Run()). Lock-step: the simulator runs their callbacks in its own
  // thread (DirectRobots::SpinRobots) whenever it waits.
  void AttachDirect(DirectRobots* robots) { direct_ = robots; }
  // Loads and validates parameters, places the initial robots, connects topics and services.
  // False (after one ROS_FATAL) on bad parameters. Initialize() and Run() must be called from
  // the same thread.
  bool Initialize();
  bool lockstep() const { return lockstep_; }
  // RobotOutlet: a directly linked robot's command and answer. From the simulator's own
  // thread (lock-step: a robot run by SpinRobots) they apply at once; from any other thread
  // (a real-time robot's worker) a command waits in a mailbox that the simulator's loop empties
  // at each step (one mutex, no callback-queue entry per robot and tick), an answer is queued
  // for the loop like a message.
  void SendCommand(std::uint16_t id, const geometry_msgs::Twist& command) override;
  void SendAnswer(std::uint16_t id, const Tick_Answer& answer) override;
  // Runs the clock until ROS shuts down.
  void Run();
  // Disconnects everything.
  void Shutdown();
  // Async-signal-safe: makes Run() return at the end of the current tick. For a SIGINT handler
  // installed instead of roscpp's, whose shutdown would silence rosconsole before Run() can
  // log its summary.
  static void RequestStop();

 private:
  // ROS is up and no stop was requested.
  static bool Running();
  // Subscribes, advertises and offers the services of the node (not the robots').
  void Connect();
  void RunRealtime();
  void RunLockstep();
  // Lock-step: the current tick's answers (zero for late robots) become the world's commands.
  void ApplyAnswers();
  // Idles after the last lock-step tick: services, markers and tf stay up.
  void Idle();

  // One radio round: Neighbors to every receiving robot, then /flock/world_poses.
  void PublishRadio();
  // At the start of a round: a flocking tuning accepted since the last one goes out with this
  // round (and on /flock/tuning); the radio's range and the markers follow its local range.
  void BeginTuningRound();
  // Lock-step: robot `id`'s answer, for the session (ignored after the last tick).
  void OnAnswer(std::uint16_t id, const core::Answer& answer);
  void PublishPoses();
  void PublishClock();
  // Markers and tf when their wall-clock period has passed, and the node's diagnostic status.
  void PublishVisualsIfDue();
  // Spins the callback queues (and, lock-step, the directly linked robots) once, waiting up to
  // `wait_s` for the first command or answer when none is queued.
  void SpinOnce(double wait_s = 0.0);
  // Lock-step: runs the directly linked robots' pending callbacks in this thread.
  void SpinRobots();
  double SimTime() const;
  ros::Time Stamp() const;

  void OnCmdVel(std::uint16_t id, const geometry_msgs::Twist& msg);
  // Runs `call` now on the simulator's thread, or queues it for its loop from another one.
  void OnSimulatorThread(std::function<void()> call);
  // Lock-step: the statists of the dispatcher's recruiting missions (SPEC 9.4) that stand at
  // this tick are relayed, those of missions that found their robots no more.
  void ApplyRecruitStatists();

  static volatile std::sig_atomic_t stop_requested_;

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  SimulatorParams params_;
  bool lockstep_ = false;
  std::unique_ptr<sim::World2D> world_;
  std::unique_ptr<core::Rng> radio_rng_;
  std::unique_ptr<sim::Radio> radio_;
  DirectRobots* direct_ = nullptr;
  std::thread::id thread_;  // Initialize()'s and Run()'s

  // cmd_vel callbacks have their own queue so that lock-step can wait for answers without
  // running services (which may spawn or kill robots) at arbitrary points.
  ros::CallbackQueue cmd_queue_;
  CommandMailbox direct_commands_;  // directly linked robots' commands from other threads
  std::unique_ptr<RobotLinks> links_;
  // Live tuning of the flocking parameters (dynamic_reconfigure on the private handle).
  std::unique_ptr<LiveTuning> tuning_;
  bool radio_follows_range_ = true;  // ~radio_range_m unset: the radio's range is the local range
  std::unique_ptr<RobotRoster> roster_;          // spawn, kill, teleports, copies and statists
  std::unique_ptr<MissionMirror> missions_;      // what the robots act on, for radio and markers
  std::unique_ptr<sim::LockstepEngine> engine_;  // the rounds (lock-step: and the relay)
  core::Round round_;                            // the round being made (its buffers kept)

  ros::Publisher positions_pub_;
  std::unique_ptr<LockstepSession> session_;  // lock-step only
  std::unique_ptr<EventPlayer> events_;       // with ~events_file only
  ros::Publisher clock_pub_;
  std::unique_ptr<sim::Visuals> visuals_;
  std::unique_ptr<NodeDiagnostics> diagnostics_;
  std::unique_ptr<LockstepHold> hold_;  // ~hold

  std::uint64_t tick_ = 0;  // radio rounds so far (lock-step: ticks)
  bool finished_ = false;   // lock-step: max ticks reached, the world is frozen
  ros::WallTime start_wall_;
  std::set<std::pair<std::uint16_t, std::uint8_t>> recruit_statists_;  // relayed now
  WarnThrottle bad_cmd_warning_;  // wall-clock throttles of repeated warnings
  WarnThrottle unsolicited_warning_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_SIMULATOR_H_
