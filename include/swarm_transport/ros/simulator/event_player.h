// Plays a scenario's timed events (the simulator's ~events_file, issue 14) into the running
// simulator at their ticks.
#ifndef SWARM_TRANSPORT_ROS_EVENT_PLAYER_H_
#define SWARM_TRANSPORT_ROS_EVENT_PLAYER_H_

#include <ros/ros.h>

#include <cstdint>
#include <vector>

#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/ros/common/event_schedule.h"
#include "swarm_transport/ros/simulator/lockstep_session.h"
#include "swarm_transport/ros/simulator/mission_mirror.h"
#include "swarm_transport/ros/simulator/robot_roster.h"

namespace swarm_transport {

// Freeze / continue / object updates / LOADED-UNLOADED go to the robots as relayed messages
// (lock-step: injected into the session's relay; real time: published as this node's
// messages); kills, spawns and statists go to the roster; an object update moves the mirrored
// mission's object too. Runs on the simulator's thread.
class EventPlayer {
 public:
  // Everything given must outlive the player; `session` is null in real time.
  EventPlayer(std::vector<TimedEvent> events, LockstepSession* session, RobotRoster* roster,
              MissionMirror* missions);

  // Real time: advertises the mission topics the events go out on, with `queue`.
  void Connect(ros::NodeHandle nh, std::uint32_t queue);
  // Applies the events due at or before `tick`, in tick order (file order within a tick).
  void ApplyDue(std::uint64_t tick);

 private:
  // Lock-step: into the session's relay; real time: on `pub` (advertised for its kind).
  void Send(const core::MissionMessage& message, const ros::Publisher& pub);

  EventSchedule schedule_;
  LockstepSession* session_;
  RobotRoster* roster_;
  MissionMirror* missions_;
  ros::Publisher freeze_pub_;  // real time only
  ros::Publisher continue_pub_;
  ros::Publisher update_pub_;
  ros::Publisher signal_pub_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_EVENT_PLAYER_H_
