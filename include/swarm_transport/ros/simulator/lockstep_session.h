// The simulator's lock-step protocol over ROS [SPEC 7]: who is live and when a tick is
// complete. The tick itself (rounds, relay, answers) is the engine's
// (sim/lockstep_engine.h), the decisions are the pure barrier's (sim/lockstep_barrier.h);
// this class feeds them from topics and the robots' links, waits, and tells observers what the
// robots said.
//
// A tick, driven by the simulator:
//   BeginTick    robots that connected become live, gone ones not; holds for the dispatcher
//   (the simulator publishes /clock and the radio: ReleaseOrders, then per robot Round,
//    deliver, Asked; then EndRound)
//   WaitForAnswers  until every live robot answered (or the timeout); their mission messages
//                go into the next round's relay, the simulator's books and observers' topics
//   CommandOf    each live robot's command for this tick
#ifndef SWARM_TRANSPORT_ROS_LOCKSTEP_SESSION_H_
#define SWARM_TRANSPORT_ROS_LOCKSTEP_SESSION_H_

#include <ros/callback_queue.h>
#include <ros/ros.h>

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/Dispatcher_Answer.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/ros/common/mission_topics.h"
#include "swarm_transport/ros/common/wall_throttle.h"
#include "swarm_transport/ros/simulator/robot_links.h"
#include "swarm_transport/ros/simulator/simulator_params.h"
#include "swarm_transport/sim/lockstep_barrier.h"
#include "swarm_transport/sim/lockstep_engine.h"
#include "swarm_transport/sim/mission_relay.h"

namespace swarm_transport {

// What the session needs of the simulator's loop while it waits.
struct LockstepHooks {
  std::function<bool()> running;      // ROS is up and no stop was requested
  std::function<void(double)> spin;   // all queues once, waiting up to s for a command
  std::function<void()> spin_robots;  // the directly linked robots' pending callbacks
  std::function<void()> visuals;      // markers and tf when due
};

class LockstepSession {
 public:
  // `links`, `command_queue` (where answers arrive) and `engine` must outlive the session.
  LockstepSession(ros::NodeHandle nh, const SimulatorParams& params, RobotLinks* links,
                  ros::CallbackQueue* command_queue, sim::LockstepEngine* engine,
                  LockstepHooks hooks);

  // Subscribes the relayed mission topics (and the dispatcher's answers), advertises the
  // observers' topics.
  void Connect();
  void Shutdown();
  // A scenario's timed event (the simulator's own message): relayed to every robot in this
  // tick's round and published for observers.
  void Inject(const core::MissionMessage& message);
  // A robot enters the barrier; after the start, one whose process already runs is waited for
  // when the next tick begins (see WaitForJoining).
  void AddRobot(std::uint16_t id);
  void RemoveRobot(std::uint16_t id);
  bool Live(std::uint16_t id) const { return barrier_.Live(id); }
  std::size_t LiveCount() const { return barrier_.LiveCount(); }

  // Before tick 0: waits until every robot is connected, `positions` has its observers and
  // every relay, every subscriber of the mission topics it publishes for observers (statuses,
  // progress, object updates and deletes, freeze / continue) and every `robot_list` subscriber
  // is connected (or the start timeout passed).
  void WaitForStart(const ros::Publisher& positions, const ros::Publisher& robot_list);
  // Tick `tick` begins: liveness, then the dispatcher's awaited events and orders.
  void BeginTick(std::uint64_t tick);
  // Statist as dispatcher (SPEC 9.4): the statists of the dispatcher's recruiting missions that
  // stand at tick `tick` (from its answers; the simulator relays them).
  std::vector<Robot_Position> RecruitStatists(std::uint64_t tick) const;
  // Round of tick `tick` (after the engine's BeginRound): StartRound, then per live robot
  // Round, its delivery, Asked; EndRound once every round is out.
  void StartRound(std::uint64_t tick) { barrier_.StartTick(tick); }
  // The round of robot `id` at world index `index`; the first after its process connected (at
  // tick 0 or when it joins or comes back) also carries the orders of the missions that have
  // not ended (MissionRelay::FillStanding).
  void Round(std::size_t index, std::uint16_t id, core::Round* round);
  void Asked(std::uint16_t id) { barrier_.Ask(id); }
  void EndRound() { engine_->EndRound(); }
  // Spins until every live robot answered tick `tick` or the timeout passed; robots that did
  // not answer are out of the barrier until they answer again.
  void WaitForAnswers(std::uint64_t tick);
  // The command a live robot drives this tick (zero when it did not answer).
  core::Velocity CommandOf(std::uint16_t id) const { return barrier_.CommandOf(id); }
  // After the last tick: nobody is asked anything, late answers are ignored.
  void Finish();
  // Robot `id`'s answer (a topic's or a direct link's), during tick `tick`.
  void OnAnswer(std::uint16_t id, const core::Answer& answer, std::uint64_t tick);

 private:
  // A mission message heard on its topic from `publisher` (an order with its start tick).
  void Relay(const core::MissionMessage& message, const std::string& publisher,
             std::uint64_t start_tick);
  void NoteStatus(std::uint16_t mission_id, core::MissionPhase phase);
  void OnDispatcherAnswer(const Dispatcher_Answer::ConstPtr& msg);
  bool RelaysConnected(const ros::Publisher& robot_list) const;
  // Robots spawned since the last tick whose process already runs (it publishes their answer
  // topic, idling until listed): waits until they are connected, as at the start.
  void WaitForJoining(std::uint64_t tick);
  void UpdateLiveness(std::uint64_t tick);
  void WaitForDispatcher(std::uint64_t tick);
  // Once a tick's answers are in: the engine takes them (next relay, books), the observers'
  // topics get their mission messages.
  void TakeAnswers();

  ros::NodeHandle nh_;
  const SimulatorParams& params_;
  RobotLinks* links_;
  ros::CallbackQueue* command_queue_;
  sim::LockstepEngine* engine_;
  LockstepHooks hooks_;
  sim::LockstepBarrier barrier_;
  sim::LockstepEngine::Answers answers_;  // not taken yet
  bool finished_ = false;
  bool started_ = false;               // WaitForStart is done
  std::set<std::uint16_t> joining_;    // added since the last tick began (after the start)
  std::set<std::uint16_t> connected_;  // became live this tick: their round carries the orders
  MissionTopics relay_topics_;
  ros::Subscriber answer_sub_;
  std::vector<core::RecruitStatist> recruiting_;  // the dispatcher's latest answer's
  // The answers' mission messages for observers (robots in lock-step publish no mission topic).
  MissionPublishers observer_topics_;
  WarnThrottle late_warning_;  // wall-clock throttles of repeated warnings
  WarnThrottle refused_warning_;
  WarnThrottle bad_answer_warning_;
  WarnThrottle unsolicited_warning_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_LOCKSTEP_SESSION_H_
