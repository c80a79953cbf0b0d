// The mission dispatcher node [SPEC 6]: accepts, validates, publishes and tracks missions, and
// sends the LOADED / UNLOADED signals.
#ifndef SWARM_TRANSPORT_ROS_MISSION_DISPATCHER_H_
#define SWARM_TRANSPORT_ROS_MISSION_DISPATCHER_H_

#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <cstdint>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/Mission_Signal.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/New_Mission.h"
#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/Submit_Mission.h"
#include "swarm_transport/core/assignment.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/core/recruit.h"
#include "swarm_transport/ros/common/diagnostics.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/common/wall_throttle.h"
#include "swarm_transport/ros/dispatcher/dispatcher_options.h"

namespace swarm_transport {

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

 private:
  bool LoadOptions(std::string* error);
  // Validates and, when accepted, tracks the mission; `publish` sends it on /flock/mission/new
  // (service and file missions; raw topic ones are already there). id 0 with `auto_id` picks
  // the next free id. `start_tick` stamps the published order (lock-step: the robots take it
  // then; 0: when it arrives).
  core::MissionBook::Verdict Submit(core::MissionSpec spec, const std::string& source, bool auto_id,
                                    bool publish, std::uint64_t start_tick = 0);
  // ... checking the robots it names against `robots` (the others: those listed now).
  core::MissionBook::Verdict Submit(core::MissionSpec spec, const std::string& source, bool auto_id,
                                    bool publish, std::uint64_t start_tick,
                                    const std::set<std::uint16_t>& robots);
  // Real time: submits the file missions of this at_tick (0: those of start_delay_s).
  void SubmitFileMissions(std::uint64_t at_tick);
  // Lock-step: submits the file missions stamped with their start tick (after the first
  // positions, of tick `tick`) and publishes the schedule the simulator holds its ticks for.
  void ScheduleFileMissions(std::uint64_t tick);
  // The physical robots of the latest /flock/positions (a mission must name only those).
  std::set<std::uint16_t> KnownRobots() const;
  // Of those, the robots on no live mission with their poses: the candidates of a count-only
  // mission (New_Mission.robot_count).
  std::map<std::uint16_t, core::PlannerRobot> IdleRobots() const;
  // Statist as dispatcher (SPEC 9.4): validates a recruiting order (core::ValidateRecruit) and,
  // accepted, places its statist at the object centre (real time: on /flock/position; lock-step:
  // the schedule tells the simulator, from `start_tick`) and watches /flock/positions.
  core::MissionBook::Verdict StartRecruit(core::MissionSpec spec, const std::string& source,
                                          bool auto_id, std::uint64_t start_tick);
  // A /flock/positions for the recruiting missions: the first robot_count idle robots inside
  // an object take its mission (its order goes out with their ids, from the next tick), its
  // statist is deleted. Lock-step: the schedule then says which tick was watched.
  void WatchRecruits(const Robot_Positions& positions);
  // Lock-step: the recruiting missions, the tick watched and the orders of `due` (id, tick).
  void PublishRecruitSchedule(std::uint64_t checked_tick,
                              const std::vector<std::pair<std::uint16_t, std::uint64_t>>& due);
  void PublishStatus(const core::MissionSpec& spec, core::MissionPhase phase,
                     const std::string& reason, std::uint64_t tick = 0);
  // Before a new order: waits (at most kListenerWaitS) until every registered subscriber of
  // the order topic is connected.
  void AwaitListeners();
  void SendEvent(std::uint16_t id, core::MissionEventKind kind, std::uint64_t not_before_tick,
                 const char* why);
  bool FromSelf(const std::string& publisher) const;

  void OnPositions(const Robot_Positions::ConstPtr& msg);
  void OnNewMission(const ros::MessageEvent<New_Mission const>& event);
  void OnStatus(const ros::MessageEvent<Mission_Status const>& event);
  // A first leader's report within a phase: robots inside, object, distance to go.
  void OnProgress(const ros::MessageEvent<Mission_Status const>& event);
  // core::MayReport for a status or progress of `mission_id` (a throttled warning when not).
  bool MayReport(const char* kind, std::uint16_t mission_id, const std::string& publisher);
  // Ends the missions whose first leader fell silent: ABORTED with the reason, Delete_Object.
  void OnWatchdog(const ros::TimerEvent& event);
  bool OnSubmit(Submit_Mission::Request& req, Submit_Mission::Response& res);
  bool OnSignal(Mission_Signal::Request& req, Mission_Signal::Response& res);
  bool OnStatusService(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  SwarmConfig config_;
  DispatcherOptions options_;
  std::vector<core::MissionSpec> file_missions_;
  std::vector<std::uint64_t> file_ticks_;  // each file mission's at_tick (0: start_delay_s)
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
  std::vector<ros::Timer> start_timers_;
  ros::Timer watchdog_timer_;
  // Missions the watchdog found silent, since when (wall time): ended after a grace period.
  std::map<std::uint16_t, ros::WallTime> silent_since_;
  ros::WallTimer status_timer_;          // its diagnostic status, once a wall second
  WarnThrottle foreign_report_warning_;  // wall-clock throttles of repeated warnings
  WarnThrottle untracked_warning_;
  std::unique_ptr<NodeDiagnostics> diagnostics_;
  ros::Publisher delete_pub_;

  Robot_Positions::ConstPtr positions_;
  // A mission gathering its robots with a statist: no robots named yet, not in the book.
  struct Recruiting {
    core::MissionSpec spec;
    core::RecruitWatch watch;
    std::string source;
    std::uint64_t start_tick = 0;  // lock-step: its statist stands from this tick
    std::uint16_t statist_id = 0;  // its statist (stacked: sub_ids 0 .. kRecruitStatistCopies-1)
  };
  std::map<std::uint16_t, Recruiting> recruiting_;
  ros::Publisher statist_pub_;               // real time: /flock/position
  ros::Publisher statist_delete_pub_;        // real time: /flock/robot/delete
  std::unique_ptr<core::MissionBook> book_;  // made by LoadOptions
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_MISSION_DISPATCHER_H_
