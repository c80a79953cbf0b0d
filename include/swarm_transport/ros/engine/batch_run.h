// Experiment runs in one process without a ROS master [issue 10, item 9; issue 25]: the
// lock-step engine that the simulator drives (sim/lockstep_engine.h), driven here with the
// robots' own sessions (core/robot_session.h), the dispatcher's book as a dispatcher without
// private parameters makes it (MissionBookParamsOf), and the recorder's bookkeeping and file
// writers (ros/recorder/recorder.h), so that a run gives the same rows and poses as a launched one
// (test/batch_equivalence.test, tick by tick) while costing no start-up: a fresh world, robots
// and generators per run, nothing kept between runs. `scripts/experiment run` uses it by
// default (--engine batch).
//
// What it leaves out, because an experiment does not use it: virtual copies and statists (no
// robot announces one yet), live tuning, real time, robots joining or leaving, missions other
// than the one the runner submits before tick 0, the dispatcher's watchdog of silent first
// leaders (no robot here falls silent), and the wall-clock waits of the ROS barrier (nothing
// here can be late).
#ifndef SWARM_TRANSPORT_ROS_BATCH_RUN_H_
#define SWARM_TRANSPORT_ROS_BATCH_RUN_H_

#include <xmlrpcpp/XmlRpcValue.h>

#include <cstdint>
#include <string>

#include "swarm_transport/New_Mission.h"
#include "swarm_transport/core/modes.h"

namespace swarm_transport {

// One run as scripts/experiment writes it into its job.json.
struct BatchJob {
  std::string kind;  // flocking | transport | leader
  std::string setting;
  int run = 0;
  std::int64_t seed = 1;
  int robots = 0;
  std::uint64_t max_ticks = 0;
  std::string config_path;  // the run's YAML, merged over the base configuration
  std::string run_dir;      // result.json, leader_track.csv, trace.csv
  std::string record_dir;   // the recorder's files go to record_dir/run_name
  std::string run_name = "run";
  core::Placement placement = core::Placement::kRandom;
  std::string placement_file;
  bool trace = false;
  bool has_mission = false;
  New_Mission mission;  // as the runner submits it (mission runs)
  int leader_id = -1;   // leader runs: the robot leading
};

// Reads a job.json. False with `error` naming the key when it is malformed.
bool ReadBatchJob(const std::string& path, BatchJob* job, std::string* error);

// Deep merge as `rosparam load` into a namespace does: dictionaries are merged key by key,
// everything else is replaced.
void MergeParams(const XmlRpc::XmlRpcValue& over, XmlRpc::XmlRpcValue* base);

// Runs `job` on `base_config` (/swarm as swarm.launch loads it before the run's YAML) and writes
// the recorder's swarm_count.csv, missions.csv and run.csv, and result.json (plus
// leader_track.csv for leader runs and trace.csv when traced), as scripts/experiment's launched
// worker does. False with `error` when the run could not be set up (bad configuration, a
// mission the dispatcher would reject, files that cannot be written); result.json then says so.
bool RunBatchJob(const BatchJob& job, const XmlRpc::XmlRpcValue& base_config, std::string* error);

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_BATCH_RUN_H_
