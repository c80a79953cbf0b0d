// The mission dispatcher node [SPEC 6]: accepts, validates, publishes and tracks missions, and
// sends the LOADED / UNLOADED signals.
#ifndef SWARM_TRANSPORT_ROS_MISSION_DISPATCHER_H_
#define SWARM_TRANSPORT_ROS_MISSION_DISPATCHER_H_

#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <array>
#include <cstdint>
#include <deque>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/Mission_Signal.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/New_Mission.h"
#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/Submit_Mission.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/ros/params.h"

namespace swarm_transport {

// Private parameters of the dispatcher (the arena and the default delays come from /swarm).
struct DispatcherOptions {
  double loaded_delay_s = 2.0;    // ~loaded_delay_s (else /swarm): LOADED after LOADING; < 0: never
  double unloaded_delay_s = 2.0;  // ~unloaded_delay_s (else /swarm): UNLOADED after UNLOADING
  std::string missions_file;      // ~missions_file: YAML with `missions:`; "" = none
  double start_delay_s = 1.0;     // ~start_delay_s: after the first /flock/positions, >= 0
  int max_live_missions = 64;     // ~max_live_missions: more are rejected, [1, 65535]
  std::string Validate() const;
};

// Reads the `missions:` list of a missions file (already turned into XmlRpc) into specs. Each
// entry: id (0 or missing = next free), robots_from + robots_to | robot_ids, leaders, object
// [x, y, size_x, size_y] (missing = leader-only), target [x, y], mode (0 | 1 | swarm |
// formation, default 0). False with `error` naming the entry and key on a malformed file.
bool MissionsFromXmlRpc(XmlRpc::XmlRpcValue& file, std::vector<core::MissionSpec>* missions,
                        std::string* error);

// What the dispatcher knows about one mission, fed by its own decisions and by the
// Mission_Status messages of the mission's first leader.
struct TrackedMission {
  core::MissionSpec spec;
  bool has_spec = false;  // false for missions first seen through a status message
  std::string source;     // service | missions_file | topic | status (order never heard)
  core::MissionPhase phase = core::MissionPhase::kQueued;
  std::string reason;
  std::uint16_t robots_assigned = 0;
  std::uint16_t robots_inside = 0;
  double distance_to_target_m = 0.0;
  // When each phase was first entered; bit p of `reached` says phase p was.
  std::array<ros::Time, 8> entered{};
  std::uint8_t reached = 0;
  bool loaded_sent = false;
  bool unloaded_sent = false;
  std::uint64_t generation = 0;  // tells a reused id's new entry from the forgotten one
  std::uint64_t phase_tick = 0;  // the first leader's tick of its latest report

  bool Live() const;
};

// Accepts missions from ~missions_file, the ~submit service and raw /flock/mission/new
// messages, validates each (ValidateMission: arena, known robots, live ids), publishes the
// accepted ones latched on /flock/mission/new (a rejected one gets a REJECTED + reason status),
// follows their phases on /flock/mission/status (each reported once by the mission's first
// leader, from QUEUED on) and their progress on /flock/mission/progress, and sends
// Mission_Event LOADED / UNLOADED after the configured delays (ros::Time: simulated under
// /use_sim_time) or on request through ~signal. ~status answers a text table. All callbacks
// run in the one ros::spin thread.
class MissionDispatcher {
 public:
  MissionDispatcher(ros::NodeHandle nh, ros::NodeHandle private_nh);
  // Loads and validates parameters and the missions file, connects topics and services.
  // False (after one ROS_FATAL) on bad input.
  bool Initialize();
  // Stops the pending timers.
  void Shutdown();

  // Completed missions kept for ~status; older ones are forgotten first.
  static constexpr std::size_t kMaxFinishedMissions = 1000;

 private:
  // The answer to one submission.
  struct Verdict {
    bool accepted = false;
    std::uint16_t id = 0;
    std::string message;
  };

  bool LoadOptions(std::string* error);
  // Validates and, when accepted, tracks the mission; `publish` sends it on /flock/mission/new
  // (service and file missions; raw topic ones are already there). id 0 with `auto_id` picks
  // the next free id. `start_tick` stamps the published order (lock-step: the robots take it
  // then; 0: when it arrives).
  Verdict Submit(core::MissionSpec spec, const std::string& source, bool auto_id, bool publish,
                 std::uint64_t start_tick = 0);
  void SubmitFileMissions();
  // Lock-step: submits the file missions stamped with their start tick (after the first
  // positions, of tick `tick`) and publishes the schedule the simulator holds its ticks for.
  void ScheduleFileMissions(std::uint64_t tick);
  core::MissionContext Context(int ignore_id = -1) const;
  std::uint16_t NextFreeId();
  void PublishStatus(const core::MissionSpec& spec, core::MissionPhase phase,
                     const std::string& reason);
  void EnterPhase(std::uint16_t id, TrackedMission* mission, core::MissionPhase phase);
  void ScheduleSignal(std::uint16_t id, TrackedMission* mission, core::MissionEventKind kind);
  // Before a new order: waits (at most kListenerWaitS) until every registered subscriber of
  // the order topic is connected.
  void AwaitListeners();
  void SendEvent(std::uint16_t id, core::MissionEventKind kind, std::uint64_t not_before_tick,
                 const char* why);
  void Forget();
  std::string StatusTable() const;
  bool FromSelf(const std::string& publisher) const;

  void OnPositions(const Robot_Positions::ConstPtr& msg);
  void OnNewMission(const ros::MessageEvent<New_Mission const>& event);
  void OnStatus(const ros::MessageEvent<Mission_Status const>& event);
  // A first leader's report within a phase: robots inside, object, distance to go.
  void OnProgress(const Mission_Status::ConstPtr& msg);
  void OnStartTimer(const ros::TimerEvent& event);
  bool OnSubmit(Submit_Mission::Request& req, Submit_Mission::Response& res);
  bool OnSignal(Mission_Signal::Request& req, Mission_Signal::Response& res);
  bool OnStatusService(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  SwarmConfig config_;
  DispatcherOptions options_;
  std::vector<core::MissionSpec> file_missions_;
  bool file_missions_scheduled_ = false;
  bool lockstep_ = false;  // /use_sim_time: the simulator's lock-step clock

  ros::Publisher new_pub_;
  ros::Publisher status_pub_;
  ros::Publisher event_pub_;
  ros::Publisher schedule_pub_;  // lock-step only
  ros::Subscriber positions_sub_;
  ros::Subscriber new_sub_;
  ros::Subscriber status_sub_;
  ros::Subscriber progress_sub_;
  ros::ServiceServer submit_srv_;
  ros::ServiceServer signal_srv_;
  ros::ServiceServer status_srv_;
  ros::Timer start_timer_;

  Robot_Positions::ConstPtr positions_;
  std::map<std::uint16_t, TrackedMission> missions_;
  // Finished missions in the order they finished: (id, generation).
  std::deque<std::pair<std::uint16_t, std::uint64_t>> finished_;
  std::uint64_t next_generation_ = 1;
  std::uint16_t next_id_ = 1;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_MISSION_DISPATCHER_H_
