// The one place that knows both worlds: message <-> core conversions (cartographer_ros style).
#ifndef SWARM_TRANSPORT_ROS_CONVERSIONS_H_
#define SWARM_TRANSPORT_ROS_CONVERSIONS_H_

#include <geometry_msgs/Twist.h>

#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include "swarm_transport/Delete_Object.h"
#include "swarm_transport/Dispatcher_Answer.h"
#include "swarm_transport/Flocking_Tuning.h"
#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/Neighbors.h"
#include "swarm_transport/New_Mission.h"
#include "swarm_transport/Pose.h"
#include "swarm_transport/Robot_Continue.h"
#include "swarm_transport/Robot_Freeze.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/Tick_Answer.h"
#include "swarm_transport/Update_Object.h"
#include "swarm_transport/core/dispatcher_answer.h"
#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_agent.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/core/swarm_config.h"

namespace swarm_transport {

// Robot_Position (angle in degrees) -> core neighbour.
core::Neighbour ToNeighbour(const Robot_Position& msg);
// Core pose of robot `id` -> Robot_Position (angle in degrees [0, 360)).
Robot_Position ToRobotPosition(std::uint16_t id, const core::Pose2& pose, std::uint8_t sub_id = 0,
                               std::uint8_t type = Robot_Position::TYPE_PHYSICAL);
// Robot_Position <-> the core's position (the same fields).
Robot_Position ToRobotPosition(const core::Position& p);
core::Position ToPosition(const Robot_Position& msg);
std::vector<Robot_Position> ToRobotPositions(const std::vector<core::Position>& positions);
// turtlesim-like Pose (theta in radians, (-pi, pi]) <-> core pose.
core::Pose2 ToPose2(const Pose& msg);
Pose ToPoseMsg(const core::Pose2& pose, const core::Velocity& velocity);
// Twist (linear.x m/s, angular.z rad/s) <-> core velocity.
core::Velocity ToVelocity(const geometry_msgs::Twist& msg);
geometry_msgs::Twist ToTwist(const core::Velocity& velocity);

// True when every float of the message is finite (the first check of every subscriber).
bool IsFinite(const Robot_Position& msg);
bool IsFinite(const geometry_msgs::Twist& msg);

// A round as robot_<id>/neighbors carries it, and back. The relayed mission messages go into
// the message's lists by kind (a round holds them in that order already); a relayed status
// carries only the mission and its phase (all a robot reads of it).
Neighbors ToNeighbors(const core::Round& round);
core::Round ToRound(const Neighbors& msg);
// Its tuning only.
std::optional<core::TuningGeneration> ToTuning(const Neighbors& msg);
// What robot `id` perceives of a round when it listens to the radio (comm local): its own
// pose, then the robots in range, those relayed hop by hop and its mission peers, each list in
// order; a position with a non-finite value is dropped (the radio relays what robots sent).
core::Perception ToPerception(std::uint16_t id, const Neighbors& msg);

// An answer as robot_<id>/answer carries it (every status stamped with the answer's tick and
// `stamp`), and back (the statuses' stamp becomes its sim_time; a command with any non-finite
// component becomes a non-finite one: the robot stands).
Tick_Answer ToTickAnswer(const core::Answer& answer, const ros::Time& stamp);
core::Answer ToAnswer(const Tick_Answer& msg);
// A Mission_Status as a status report (without its tick and stamp).
core::StatusReport ToStatusReport(const Mission_Status& msg);
// A status report of tick `tick`, stamped `stamp`.
Mission_Status ToStatusMsg(const core::StatusReport& report, std::uint64_t tick,
                           const ros::Time& stamp);

// A first leader's (or the dispatcher's) Mission_Status -> the report the dispatcher books.
core::MissionReport ToMissionReport(const Mission_Status& msg);

// Flocking_Tuning <-> the core's live flocking parameters (generation and tick are the relay's).
core::FlockingTuning ToFlockingTuning(const Flocking_Tuning& msg);
Flocking_Tuning ToTuningMsg(const core::FlockingTuning& tuning, std::uint32_t generation,
                            std::uint64_t tick);

// A core mission message -> its message (a status: its mission and phase only).
New_Mission ToMsg(const core::MissionSpec& m);
Update_Object ToMsg(const core::ObjectUpdate& m);
Delete_Object ToMsg(const core::ObjectDelete& m);
Robot_Freeze ToMsg(const core::Freeze& m);
Robot_Continue ToMsg(const core::Continue& m);
Mission_Event ToMsg(const core::Signal& m);
Mission_Status ToMsg(const core::PhaseStatus& m);
// The message type of a core mission message kind (MsgOf<core::Freeze> is its ROS message).
template <typename C>
using MsgOf = decltype(ToMsg(std::declval<const C&>()));

// New_Mission -> core mission; all_finite records whether every float of the message is finite
// (ValidateMission rejects the mission otherwise).
core::MissionSpec ToMissionSpec(const New_Mission& msg);
// A mission message -> the core's one inbox type (core/mission_message.h).
core::MissionMessage ToMissionMessage(const New_Mission& msg);
core::MissionMessage ToMissionMessage(const Update_Object& msg);
core::MissionMessage ToMissionMessage(const Delete_Object& msg);
core::MissionMessage ToMissionMessage(const Robot_Freeze& msg);
core::MissionMessage ToMissionMessage(const Robot_Continue& msg);
core::MissionMessage ToMissionMessage(const Mission_Event& msg);
core::MissionMessage ToMissionMessage(const Mission_Status& msg);
// A lock-step round's relayed mission messages in the order a robot takes them (Neighbors.msg):
// missions, object updates, object deletes, freezes, continues, events, statuses.
std::vector<core::MissionMessage> ToMissionMessages(const Neighbors& round);
// The dispatcher's lock-step answer (core/dispatcher_answer.h) <-> Dispatcher_Answer.
Dispatcher_Answer ToMsg(const core::DispatcherAnswer& answer);
core::DispatcherAnswer ToDispatcherAnswer(const Dispatcher_Answer& msg);
// A recruit's statist (TYPE_STATIST) at `at`, its copy `sub_id`.
Robot_Position StatistPosition(std::uint16_t statist_id, core::Vec2 at, std::uint8_t sub_id);
// Who published a mission message, from its publisher's node name (MessageEvent): the
// dispatcher (names::kDispatcherNode), the simulator or a robot host (relay: they carry robots'
// messages), a robot's node (/robot_<id>/robot), else other.
core::Sender SenderOf(const std::string& node_name);
// Core mission -> New_Mission (robot_ids sent only when the spec has them).
New_Mission ToNewMission(const core::MissionSpec& spec);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_CONVERSIONS_H_
