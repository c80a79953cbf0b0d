// The mission dispatcher's configuration: its private parameters with the /swarm defaults, and
// its missions file. Read and validated here, before the node connects anything.
#ifndef SWARM_TRANSPORT_ROS_DISPATCHER_OPTIONS_H_
#define SWARM_TRANSPORT_ROS_DISPATCHER_OPTIONS_H_

#include <ros/node_handle.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <map>
#include <string>
#include <vector>

#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/core/dispatcher_policy.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/ros/common/event_schedule.h"
#include "swarm_transport/ros/common/params.h"

namespace swarm_transport {

// Private parameters of the dispatcher (the arena and the default delays come from /swarm).
struct DispatcherOptions {
  double loaded_delay_s = 2.0;    // ~loaded_delay_s (else /swarm): LOADED after LOADING; < 0: never
  double unloaded_delay_s = 2.0;  // ~unloaded_delay_s (else /swarm): UNLOADED after UNLOADING
  std::string missions_file;      // ~missions_file: YAML with `missions:`; "" = none
  // ~events_file: the simulator's timed events (a scenario's; "" = none). In lock-step a file
  // mission is checked against the robots of its start tick as the spawns and kills make them.
  std::string events_file;
  std::vector<TimedEvent> events;  // ... read from it
  double start_delay_s = 1.0;      // ~start_delay_s: after the first /flock/world_poses, >= 0
  int max_live_missions = 64;      // ~max_live_missions (else /swarm's): more are rejected
  // ~silent_abort_ticks: a running mission whose first leader said nothing (phase or progress
  // report, one every 50 ticks) for this many ticks is ABORTED - its first leader is lost
  // (issue 11); 0: never.
  int silent_abort_ticks = 300;
  std::string Validate() const;
};

// Reads the `missions:` list of a missions file (already turned into XmlRpc) into specs. Each
// entry: id (0 or missing = next free), robots_from + robots_to | robot_ids, leaders, object
// [x, y, size_x, size_y] (missing = leader-only), target [x, y], mode (0 | 1 | swarm |
// formation, default 0), at_tick (lock-step: the tick the robots take it; real time: that many
// ticks' worth of time after the first positions; 0 or missing: ~start_delay_s) into
// `at_ticks` when given. False with `error` naming the entry and key on a malformed file.
bool MissionsFromXmlRpc(XmlRpc::XmlRpcValue& file, std::vector<core::MissionSpec>* missions,
                        std::string* error, std::vector<std::uint64_t>* at_ticks = nullptr);

// Reads ~missions_file (a YAML path) into specs and checks what can be checked before any robot
// is known: each mission valid in an arena of `world_size_m`, no id twice. False with `error`
// starting "~missions_file" and naming the path and the entry.
bool ReadMissionsFile(const std::string& path, double world_size_m,
                      std::vector<core::MissionSpec>* missions, std::string* error,
                      std::vector<std::uint64_t>* at_ticks = nullptr);

// Reads /swarm through `nh` into `config` and the private parameters through `private_nh` into
// `options` (the delays default to /swarm's), then validates them and reads the missions file.
bool ReadDispatcherOptions(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh,
                           SwarmConfig* config, DispatcherOptions* options,
                           std::vector<core::MissionSpec>* file_missions, std::string* error,
                           std::vector<std::uint64_t>* file_ticks = nullptr);

// The options of a dispatcher without private parameters: its delays and live-mission limit
// are /swarm's (`config`), the rest the defaults above.
DispatcherOptions DispatcherOptionsOf(const SwarmConfig& config);

// The mission book the options describe.
core::MissionBookParams MissionBookParamsOf(const SwarmConfig& config,
                                            const DispatcherOptions& options);

// The dispatcher's policy the options describe (its clock is the caller's to set).
core::DispatcherPolicyParams DispatcherPolicyParamsOf(const SwarmConfig& config,
                                                      const DispatcherOptions& options,
                                                      bool lockstep);

// A delay for the log: "after S s", or "on a signal only" when negative.
std::string DelayText(double s);

// Why the dispatcher ignores a first leader's Mission_Status (an unknown state, a field that is
// not finite), or empty.
std::string StatusProblem(const Mission_Status& status);

// The physical robots of a /flock/world_poses with their poses, by id: the swarm the policy knows.
std::map<std::uint16_t, core::PlannerRobot> SwarmOf(const std::vector<Robot_Position>& robots);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_DISPATCHER_OPTIONS_H_
