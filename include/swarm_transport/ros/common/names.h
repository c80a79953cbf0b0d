// Default topic, service and frame names in one place. Per-robot names are relative: they are
// resolved inside the robot's namespace (robot_<id>), like turtlesim's multisim.launch.
#ifndef SWARM_TRANSPORT_ROS_NAMES_H_
#define SWARM_TRANSPORT_ROS_NAMES_H_

#include <cstdint>
#include <string>

namespace swarm_transport {
namespace names {

// Global topics (SPEC 3).
constexpr char kPosition[] = "/flock/position";
constexpr char kWorldPoses[] = "/flock/world_poses";  // aggregated, from the simulator
constexpr char kRobots[] = "/flock/robots";           // latched: the robots that exist
constexpr char kMissionNew[] = "/flock/mission/new";
constexpr char kMissionStatus[] = "/flock/mission/status";      // each phase once, on entry
constexpr char kMissionProgress[] = "/flock/mission/progress";  // periodic, within a phase
constexpr char kMissionEvent[] = "/flock/mission/event";
// A restarted dispatcher's or recorder's request (latched) and the first leaders' answers.
constexpr char kMissionResendRequest[] = "/flock/mission/resend_request";
constexpr char kMissionResent[] = "/flock/mission/resent";
constexpr char kDispatcherAnswer[] = "/flock/dispatcher/answer";  // latched, lock-step
constexpr char kFreeze[] = "/flock/freeze";
constexpr char kContinue[] = "/flock/continue";
constexpr char kObjectUpdate[] = "/flock/object/update";
constexpr char kObjectDelete[] = "/flock/object/delete";
constexpr char kRobotNew[] = "/flock/robot/new";
constexpr char kRobotDelete[] = "/flock/robot/delete";
constexpr char kMarkers[] = "/flock/markers";
constexpr char kStats[] = "/flock/stats";      // the recorder's Swarm_Stats
constexpr char kObjects[] = "/flock/objects";  // Mission_Objects, per tick, on demand
constexpr char kTuning[] = "/flock/tuning";    // latched: the live flocking tuning (issue 13)
constexpr char kRobotStats[] = "/flock/robot_stats";  // robots' diagnostics lines (benchmarks)

// Per robot, relative to the robot's namespace.
constexpr char kCmdVel[] = "cmd_vel";
constexpr char kPose[] = "pose";
constexpr char kNeighbors[] = "neighbors";
constexpr char kAnswer[] = "answer";  // lock-step only: Tick_Answer
constexpr char kTeleportAbsolute[] = "teleport_absolute";
constexpr char kTeleportRelative[] = "teleport_relative";

// Simulator services (global).
constexpr char kSpawn[] = "/spawn";
constexpr char kKill[] = "/kill";
constexpr char kReset[] = "/reset";

// Node names the mission messages' senders are told by (core::Sender).
constexpr char kDispatcherNode[] = "/mission_dispatcher";
constexpr char kSimulatorNode[] = "/simulator";
constexpr char kRobotHostNodePrefix[] = "/robot_host";  // "/robot_host", "/robot_host_<name>"
constexpr char kRobotNodeName[] = "robot";              // a robot's node: /robot_<id>/robot

// Dispatcher services.
constexpr char kSubmitMission[] = "/mission_dispatcher/submit";
constexpr char kSignalMission[] = "/mission_dispatcher/signal";

// tf frames.
constexpr char kWorldFrame[] = "world";
constexpr char kBaseLink[] = "base_link";

// The namespace of robot `id`: "robot_<id>".
inline std::string RobotNamespace(std::uint16_t id) { return "robot_" + std::to_string(id); }

}  // namespace names
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_NAMES_H_
