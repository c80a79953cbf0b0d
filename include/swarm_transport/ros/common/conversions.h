// The one place that knows both worlds: message <-> core conversions (cartographer_ros style).
#ifndef SWARM_TRANSPORT_ROS_CONVERSIONS_H_
#define SWARM_TRANSPORT_ROS_CONVERSIONS_H_

#include <geometry_msgs/Twist.h>

#include <cstdint>
#include <vector>

#include "swarm_transport/Delete_Object.h"
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
#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_agent.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/core/swarm_config.h"
#include "swarm_transport/sim/radio.h"

namespace swarm_transport {

// Robot_Position (angle in degrees) -> core neighbour.
core::Neighbour ToNeighbour(const Robot_Position& msg);
// Core pose of robot `id` -> Robot_Position (angle in degrees [0, 360)).
Robot_Position ToRobotPosition(std::uint16_t id, const core::Pose2& pose, std::uint8_t sub_id = 0,
                               std::uint8_t type = Robot_Position::TYPE_PHYSICAL);
// turtlesim-like Pose (theta in radians, (-pi, pi]) <-> core pose.
core::Pose2 ToPose2(const Pose& msg);
Pose ToPoseMsg(const core::Pose2& pose, const core::Velocity& velocity);
// Twist (linear.x m/s, angular.z rad/s) <-> core velocity.
core::Velocity ToVelocity(const geometry_msgs::Twist& msg);
geometry_msgs::Twist ToTwist(const core::Velocity& velocity);

// True when every float of the message is finite (the first check of every subscriber).
bool IsFinite(const Robot_Position& msg);
bool IsFinite(const geometry_msgs::Twist& msg);

// A robot's Neighbors message of tick `tick` without the relayed mission messages: its own pose
// and what the radio decided (`robots`, `relayed`, `mission_peers`); `truth` holds the round's
// physical robots as positions (index = the radio's robot index), `extras` its relayed extras. The
// simulator and the in-process batch runner build every robot's round with this, so both hand a
// robot the same bytes.
Neighbors RadioRoundMessage(std::uint64_t tick, double sim_time, const sim::Robot& robot,
                            const sim::RadioRound& round, const std::vector<Robot_Position>& truth,
                            const std::vector<Robot_Position>& extras);
// What robot `id` perceives of a round when it listens to the radio (comm local): its own
// pose, then the robots in range, those relayed hop by hop and its mission peers, each list in
// order; a position with a non-finite value is dropped (the radio relays what robots sent).
core::Perception ToPerception(std::uint16_t id, const Neighbors& msg);

// What a first leader says in tick `tick`, as messages (a Tick_Answer's lists, without tick
// and command): its outbox (statuses already sequenced: one per phase) and its progress
// reports, every status stamped `tick` and `stamp`. The robot node and the batch engine both
// build them here.
Tick_Answer ToAnswerMessages(const core::MissionOutbox& outbox,
                             const std::vector<core::StatusReport>& progress, std::uint64_t tick,
                             const ros::Time& stamp);

// A LOADED / UNLOADED the dispatcher's book made due -> its Mission_Event.
Mission_Event ToEventMsg(const core::DueSignal& due);
// A first leader's (or the dispatcher's) Mission_Status -> the report the dispatcher books.
core::MissionReport ToMissionReport(const Mission_Status& msg);

// Flocking_Tuning <-> the core's live flocking parameters (generation and tick are the relay's).
core::FlockingTuning ToFlockingTuning(const Flocking_Tuning& msg);
Flocking_Tuning ToTuningMsg(const core::FlockingTuning& tuning, std::uint32_t generation,
                            std::uint64_t tick);

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
// Who published a mission message, from its publisher's node name (MessageEvent): the
// dispatcher (names::kDispatcherNode), the simulator or a robot host (relay: they carry robots'
// messages), a robot's node (/robot_<id>/robot), else other.
core::Sender SenderOf(const std::string& node_name);
// Core mission -> New_Mission (robot_ids sent only when the spec has them).
New_Mission ToNewMission(const core::MissionSpec& spec);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_CONVERSIONS_H_
