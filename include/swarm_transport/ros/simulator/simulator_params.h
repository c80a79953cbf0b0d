// The simulator's configuration: the shared /swarm configuration plus its private parameters,
// read and validated in one place.
#ifndef SWARM_TRANSPORT_ROS_SIMULATOR_PARAMS_H_
#define SWARM_TRANSPORT_ROS_SIMULATOR_PARAMS_H_

#include <ros/node_handle.h>

#include <string>

#include "swarm_transport/core/modes.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/sim/radio.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {

// Everything the simulator is configured with: the shared /swarm configuration plus its
// private parameters (~name), units in the names.
struct SimulatorParams {
  SwarmConfig swarm;        // /swarm: world size, radius, range, tick, seed, zones
  double radio_loss = 0.0;  // /swarm/radio_loss: drop probability per message, [0, 1]
  int robots = 0;           // ~robots: initial robots, ids 0..robots-1
  core::Placement placement = core::Placement::kRandom;  // ~placement: random | corner | file
  std::string placement_file;                            // ~placement_file: lines "x y theta_deg"
  // ~events_file: timed events of a scenario (event_schedule.h), applied at their ticks.
  std::string events_file;
  core::Clock clock = core::Clock::kRealtime;  // ~clock: realtime | lockstep
  double lockstep_timeout_s = 2.0;  // ~lockstep_timeout_s: wait this long for a tick's answers
  int lockstep_max_ticks = 0;       // ~lockstep_max_ticks: stop ticking after this many (0: never)
  // ~lockstep_observers: also wait until /flock/world_poses has this many subscribers (a
  // recorder, a test, the demo) so that nobody misses the first ticks.
  int lockstep_observers = 0;
  double lockstep_start_timeout_s = 60.0;  // ~lockstep_start_timeout_s: wait for robots to connect
  // ~real_time_factor: lock-step pacing, simulated seconds per wall second (1.0: real time, to
  // watch a deterministic run in rviz and send commands by hand; 0: as fast as possible).
  double real_time_factor = 0.0;
  // ~hold_at: lock-step, the run holds before this tick from the start, as a ~hold asked before
  // tick 0 would (a test or a tool that acts at a stated tick cannot miss it however fast the
  // run goes); ~hold with tick 0 releases it. 0: no hold.
  int hold_at = 0;
  // ~lockstep_dispatcher: a mission dispatcher runs; ticks wait for its answers
  // (Dispatcher_Answer) and what they name, so that its LOADED / UNLOADED and orders apply at
  // their stamped ticks however loaded the machine is.
  bool lockstep_dispatcher = false;
  double integration_step_s = 0.01;  // ~integration_step_s: world sub-step (real time: loop period)
  double markers_rate_hz = 10.0;     // ~markers_rate_hz: markers and tf, wall clock (0: off)
  bool tf = true;                    // ~tf: broadcast world -> robot_<id>/base_link
  bool range_circles = false;        // ~range_circles: draw each robot's local range
  int trail_ticks = 0;               // ~trail_ticks: a line through each robot's last positions
  double radio_range_m = 1.0;        // ~radio_range_m: default /swarm/local_range_m
  // ~pose_topics: advertise robot_<id>/pose for every robot. Default true, false when robots
  // are linked directly (a robot_host that runs the simulator): a publication per robot costs
  // roscpp time in every publish of the process, and /flock/world_poses carries every pose.
  bool pose_topics = true;

  // Empty when valid, else one sentence naming the first bad parameter and its accepted range.
  std::string Validate() const;
};

// Reads /swarm (and /swarm/radio_loss) through `nh` and the private parameters through
// `private_nh`, then validates. `direct`: robots are linked directly (the default of
// ~pose_topics is then false). False with `error` naming the first bad parameter.
bool ReadSimulatorParams(const ros::NodeHandle& nh, const ros::NodeHandle& private_nh, bool direct,
                         SimulatorParams* params, std::string* error);
// The world and the radio the parameters describe.
sim::WorldParams WorldParamsOf(const SimulatorParams& params);
sim::RadioParams RadioParamsOf(const SimulatorParams& params);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_SIMULATOR_PARAMS_H_
