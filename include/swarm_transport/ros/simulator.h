// The simulator node: adapts the pure World2D to ROS, owns the clock and plays the radio.
#ifndef SWARM_TRANSPORT_ROS_SIMULATOR_H_
#define SWARM_TRANSPORT_ROS_SIMULATOR_H_

#include <geometry_msgs/Twist.h>
#include <ros/callback_queue.h>
#include <ros/ros.h>
#include <std_srvs/Empty.h>

#include <csignal>
#include <cstdint>
#include <functional>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "swarm_transport/Delete_Object.h"
#include "swarm_transport/Delete_Robot.h"
#include "swarm_transport/Kill.h"
#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/Mission_Schedule.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/Neighbors.h"
#include "swarm_transport/New_Mission.h"
#include "swarm_transport/Robot_Continue.h"
#include "swarm_transport/Robot_Freeze.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/Spawn.h"
#include "swarm_transport/TeleportAbsolute.h"
#include "swarm_transport/TeleportRelative.h"
#include "swarm_transport/Tick_Answer.h"
#include "swarm_transport/Update_Object.h"
#include "swarm_transport/core/modes.h"
#include "swarm_transport/core/random.h"
#include "swarm_transport/ros/direct_link.h"
#include "swarm_transport/ros/params.h"
#include "swarm_transport/sim/live_mission.h"
#include "swarm_transport/sim/lockstep_barrier.h"
#include "swarm_transport/sim/radio.h"
#include "swarm_transport/ros/visuals.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {

// Everything the simulator is configured with: the shared /swarm configuration plus its
// private parameters (~name), units in the names.
struct SimulatorParams {
  SwarmConfig swarm;                 // /swarm: world size, radius, range, tick, seed, zones
  double radio_loss = 0.0;           // /swarm/radio_loss: drop probability per message, [0, 1]
  int robots = 0;                    // ~robots: initial robots, ids 0..robots-1
  core::Placement placement = core::Placement::kRandom;  // ~placement: random | corner | file
  std::string placement_file;        // ~placement_file: lines "x y theta_deg"
  core::Clock clock = core::Clock::kRealtime;  // ~clock: realtime | lockstep
  double lockstep_timeout_s = 2.0;   // ~lockstep_timeout_s: wait this long for a tick's answers
  int lockstep_max_ticks = 0;        // ~lockstep_max_ticks: stop ticking after this many (0: never)
  // ~lockstep_observers: also wait until /flock/positions has this many subscribers (a
  // recorder, a test, the demo) so that nobody misses the first ticks.
  int lockstep_observers = 0;
  double lockstep_start_timeout_s = 60.0;  // ~lockstep_start_timeout_s: wait for robots to connect
  // ~real_time_factor: lock-step pacing, simulated seconds per wall second (1.0: real time, to
  // watch a deterministic run in rviz and send commands by hand; 0: as fast as possible).
  double real_time_factor = 0.0;
  // ~lockstep_dispatcher: a mission dispatcher answers LOADING / UNLOADING with a stamped
  // LOADED / UNLOADED (/swarm/loaded_delay_s, unloaded_delay_s >= 0); hold the next tick until
  // it arrived (at most lockstep_timeout_s), so that it applies at its stamped tick however
  // loaded the machine is.
  bool lockstep_dispatcher = false;
  double integration_step_s = 0.01;  // ~integration_step_s: world sub-step (real time: loop period)
  double markers_rate_hz = 10.0;     // ~markers_rate_hz: markers and tf, wall clock (0: off)
  bool tf = true;                    // ~tf: broadcast world -> robot_<id>/base_link
  bool range_circles = false;        // ~range_circles: draw each robot's local range
  double radio_range_m = 1.0;        // ~radio_range_m: default /swarm/local_range_m
  // ~pose_topics: advertise robot_<id>/pose for every robot. Default true, false when robots
  // are linked directly (a robot_host that runs the simulator): a publication per robot costs
  // roscpp time in every publish of the process, and /flock/positions carries every pose.
  bool pose_topics = true;

  // Empty when valid, else one sentence naming the first bad parameter and its accepted range.
  std::string Validate() const;
};

// The turtlesim-like simulator [SPEC 7]: per-robot cmd_vel, pose, neighbors and teleport
// services, global spawn/kill/reset, /flock/positions, markers, tf, and in lock-step /clock.
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
  // thread (lock-step: a robot run by SpinRobots) they apply at once, from any other thread
  // they are queued for the simulator's loop like a cmd_vel message.
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
  // The ROS side of one robot (or its direct link); its lock-step bookkeeping is barrier_'s.
  struct RobotIo {
    bool direct = false;  // linked directly: no neighbors, cmd_vel or answer topics
    ros::Publisher neighbors;
    ros::Publisher pose;
    ros::Subscriber cmd_vel;
    ros::ServiceServer teleport_absolute;
    ros::ServiceServer teleport_relative;
    // Connected subscribers, counted by connect / disconnect callbacks: getNumSubscribers()
    // scans every publication of the node, O(robots) per call.
    int neighbors_subscribers = 0;
    int pose_subscribers = 0;
    std::uint64_t generation = 0;      // tells this robot's callbacks from a killed namesake's
    ros::WallTime connected_since;     // lock-step: both links up since (zero: not connected)
    // Lock-step: it let a tick time out and is out of the barrier until it answers again (a
    // hung robot costs lockstep_timeout_s once, not every tick; issue 11).
    bool silent = false;
    ros::Subscriber answer;            // lock-step: its Tick_Answer
  };
  using Mission = sim::LiveMission;
  using RelayKey = std::pair<std::uint16_t, std::uint8_t>;  // (robot_id, sub_id)
  // Lock-step: mission messages received this tick, with their sender, to relay in the next
  // Neighbors (stable-sorted by sender: per sender and topic, arrival is FIFO). Senders are
  // publishing nodes ("/mission_dispatcher") or robots' answers (AnswerSender: after them, by
  // robot id).
  template <typename M>
  using RelayList = std::vector<std::pair<std::string, M>>;

  // ROS is up and no stop was requested.
  static bool Running();
  bool LoadParams(std::string* error);
  bool PlaceInitialRobots(std::string* error);
  void AddRobotIo(std::uint16_t id);
  // Counts a (dis)connected subscriber of robot `id`'s `field` (+1 / -1).
  void CountSubscriber(std::uint16_t id, std::uint64_t generation, int RobotIo::*field, int delta);
  // Lock-step: the robot has listened to its Neighbors and published its answers for kSettleS.
  bool Ready(RobotIo* io);
  void RemoveRobot(std::uint16_t id);

  void RunRealtime();
  void RunLockstep();
  // Lock-step: waits until every robot is connected (or the start timeout passed).
  void WaitForRobots();
  // Lock-step start: every node the master lists as a publisher of a relayed mission topic
  // (the robots' outlets, a dispatcher, a test) is connected to this simulator's relay, and
  // every subscriber of the robot list is connected (it got the latched list).
  bool RelaysConnected() const;
  // Lock-step: marks connected robots live and disconnected ones not live.
  void UpdateLiveness();
  // Lock-step: spins until every live robot answered the current tick or the timeout passed.
  void WaitForAnswers();
  // Lock-step: holds until every awaited dispatcher event arrived (at most lockstep_timeout_s)
  // and, from tick 1, the dispatcher's schedule and every order due by this tick (at most
  // lockstep_start_timeout_s).
  void WaitForDispatcher();
  void OnSchedule(const Mission_Schedule::ConstPtr& msg);
  // Lock-step: the received orders due by this tick enter its relay and the books.
  void ReleaseMissions();
  // Lock-step bookkeeping of awaited dispatcher events, from relayed statuses and events.
  void NoteStatus(const Mission_Status& status);
  void NoteEvent(const Mission_Event& event);
  // Lock-step: the current tick's answers (zero for late robots) become the world's commands.
  void ApplyAnswers();
  // Idles after the last lock-step tick: services, markers and tf stay up.
  void Idle();

  // One radio round: Neighbors to every receiving robot, then /flock/positions.
  void PublishRadio();
  // Lock-step relay of mission messages (Neighbors.msg): record one, fill a perception, clear.
  template <typename M>
  void Relay(const ros::MessageEvent<const M>& event, RelayList<M>* list);
  void FillRelay(Neighbors* msg) const;
  void ClearRelay();
  // Lock-step: robot `id`'s answer (its command counts for the barrier; its mission messages,
  // also those of a late answer, are kept for TakeAnswers).
  void OnAnswer(std::uint16_t id, const Tick_Answer& answer);
  // Lock-step, once a tick's answers are in: their mission messages, by robot id, into the next
  // relay, the simulator's own books and the observers' topics.
  void TakeAnswers();
  // Latched /flock/robots: the robots that exist (robots check missions against it).
  void PublishRobotList();
  void PublishPoses();
  void PublishClock();
  // Markers and tf when their wall-clock period has passed.
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
  bool OnSpawn(Spawn::Request& req, Spawn::Response& res);
  bool OnKill(Kill::Request& req, Kill::Response& res);
  bool OnReset(std_srvs::Empty::Request& req, std_srvs::Empty::Response& res);
  bool OnTeleportAbsolute(std::uint16_t id, TeleportAbsolute::Request& req,
                          TeleportAbsolute::Response& res);
  bool OnTeleportRelative(std::uint16_t id, TeleportRelative::Request& req,
                          TeleportRelative::Response& res);
  void OnPosition(const Robot_Position::ConstPtr& msg);
  void OnRobotDelete(const Delete_Robot::ConstPtr& msg);
  void OnMissionNew(const New_Mission::ConstPtr& msg);
  // Validated like the robots do: a valid order gets its mission channel and markers.
  void RegisterMission(const New_Mission& order);
  void OnObjectUpdate(const Update_Object::ConstPtr& msg);
  void OnObjectDelete(const Delete_Object::ConstPtr& msg);

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
  std::map<std::uint16_t, RobotIo> io_;
  std::map<RelayKey, Robot_Position> relayed_;  // virtual copies (type 1) and statists (type 2)
  sim::LiveMissions missions_;

  ros::Publisher positions_pub_;
  ros::Publisher robots_pub_;
  std::vector<ros::Subscriber> relay_subs_;
  RelayList<New_Mission> pending_missions_;  // received, waiting for their start tick
  RelayList<New_Mission> relay_missions_;
  RelayList<Update_Object> relay_updates_;
  RelayList<Delete_Object> relay_deletes_;
  RelayList<Robot_Freeze> relay_freezes_;
  RelayList<Robot_Continue> relay_continues_;
  RelayList<Mission_Event> relay_events_;
  RelayList<Mission_Status> relay_statuses_;
  std::vector<std::pair<std::uint16_t, Tick_Answer>> answers_;  // lock-step: not taken yet
  // Lock-step: the answers' mission messages for observers.
  ros::Publisher status_pub_;
  ros::Publisher progress_pub_;
  ros::Publisher update_pub_;
  ros::Publisher delete_pub_;
  ros::Publisher freeze_pub_;
  ros::Publisher continue_pub_;
  sim::LockstepBarrier barrier_;
  ros::Publisher clock_pub_;
  std::unique_ptr<sim::Visuals> visuals_;
  ros::ServiceServer spawn_srv_;
  ros::ServiceServer kill_srv_;
  ros::ServiceServer reset_srv_;
  ros::Subscriber position_sub_;
  ros::Subscriber robot_delete_sub_;
  ros::Subscriber mission_new_sub_;
  ros::Subscriber schedule_sub_;
  ros::Subscriber object_update_sub_;
  ros::Subscriber object_delete_sub_;

  std::uint64_t next_generation_ = 0;
  std::uint64_t tick_ = 0;    // radio rounds so far (lock-step: ticks)
  bool finished_ = false;     // lock-step: max ticks reached, the world is frozen
  ros::WallTime start_wall_;
  ros::WallTime last_late_warning_wall_;  // wall-clock throttles of repeated warnings
  ros::WallTime last_bad_cmd_warning_wall_;
  ros::WallTime last_unsolicited_warning_wall_;
  ros::WallTime last_bad_position_warning_wall_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_SIMULATOR_H_
