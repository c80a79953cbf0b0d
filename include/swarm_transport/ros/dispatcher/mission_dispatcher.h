// The mission dispatcher node [SPEC 6]: accepts, validates, publishes and tracks missions, and
// sends the LOADED / UNLOADED signals.
#ifndef SWARM_TRANSPORT_ROS_MISSION_DISPATCHER_H_
#define SWARM_TRANSPORT_ROS_MISSION_DISPATCHER_H_

#include <ros/ros.h>
#include <std_srvs/Trigger.h>
#include <xmlrpcpp/XmlRpcValue.h>

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "swarm_transport/Mission_Signal.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/New_Mission.h"
#include "swarm_transport/Robot_Positions.h"
#include "swarm_transport/Submit_Mission.h"
#include "swarm_transport/core/dispatcher_policy.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/ros/common/diagnostics.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/common/wall_throttle.h"
#include "swarm_transport/ros/dispatcher/dispatcher_options.h"
#include "swarm_transport/ros/dispatcher/dispatcher_rebuild.h"
#include "swarm_transport/ros/dispatcher/order_publisher.h"

namespace swarm_transport {

// Accepts missions from ~missions_file, the ~submit service and raw /flock/mission/new
// messages, validates each (ValidateMission: arena, known robots, live ids), publishes the
// accepted ones latched on /flock/mission/new (a rejected one gets a REJECTED + reason status),
// follows their phases on /flock/mission/status (each reported once by the mission's first
// leader, from QUEUED on) and their progress on /flock/mission/progress, and sends
// Mission_Event LOADED / UNLOADED after the configured delays (ros::Time: simulated under
// /use_sim_time) or on request through ~signal. ~status answers a text table. All callbacks
// run in the one ros::spin thread.
// Restarted on the same master in real time, it first rebuilds its table from the first
// leaders' re-sent statuses and only then takes orders, submissions and
// statuses, held in their queues meanwhile (DispatcherRebuild, docs/reliability.md).
// Its policy (what it accepts, picks, recruits, schedules and sends) is the pure
// core::DispatcherPolicy; this node moves bytes between ROS and it.
class MissionDispatcher : private core::DispatcherOutlet {
 public:
  MissionDispatcher(ros::NodeHandle nh, ros::NodeHandle private_nh);
  // Loads and validates parameters and the missions file, connects topics and services.
  // False (after one ROS_FATAL) on bad input.
  bool Initialize();
  // Stops the pending timers.
  void Shutdown();

 private:
  static constexpr char kNode[] = "mission_dispatcher";
  static const char* SignalName(core::MissionEventKind kind) {
    return kind == core::MissionEventKind::kLoaded ? "LOADED" : "UNLOADED";
  }

  // core::DispatcherOutlet: what the policy decided, carried out over ROS
  // (dispatcher_outlets.cpp).
  void Order(const core::MissionSpec& spec, std::uint64_t start_tick) override;
  void Rejected(const core::MissionSpec& spec, const std::string& reason) override;
  void Aborted(const core::MissionSpec& spec, const std::string& reason) override;
  void Event(const core::Signal& signal, const char* why) override;
  void StatistUp(std::uint16_t statist_id, core::Vec2 at, int copies) override;
  void StatistDown(std::uint16_t statist_id, int copies) override;
  void Answer(const core::DispatcherAnswer& answer) override;
  void Log(bool warn, const std::string& text) override;

  void PublishStatus(const core::MissionSpec& spec, core::MissionPhase phase,
                     const std::string& reason, std::uint64_t tick = 0);
  bool FromSelf(const std::string& publisher) const {
    return publisher == ros::this_node::getName();
  }

  void OnPositions(const Robot_Positions::ConstPtr& msg);
  void OnNewMission(const ros::MessageEvent<New_Mission const>& event);
  void OnStatus(const ros::MessageEvent<Mission_Status const>& event);
  // A first leader's report within a phase: robots inside, object, distance to go.
  void OnProgress(const ros::MessageEvent<Mission_Status const>& event);
  // core::MayReport for a status or progress of `mission_id` (a throttled warning when not).
  bool MayReport(const char* kind, std::uint16_t mission_id, const std::string& publisher);
  bool OnSubmit(Submit_Mission::Request& req, Submit_Mission::Response& res);
  bool OnSignal(Mission_Signal::Request& req, Mission_Signal::Response& res);
  bool OnStatusService(std_srvs::Trigger::Request& req, std_srvs::Trigger::Response& res);

  ros::NodeHandle nh_;
  ros::NodeHandle private_nh_;
  SwarmConfig config_;
  DispatcherOptions options_;
  std::unique_ptr<core::DispatcherPolicy> policy_;  // made by Initialize
  bool lockstep_ = false;  // /use_sim_time: the simulator's lock-step clock

  std::unique_ptr<OrderPublisher> orders_;      // /flock/mission/new
  std::unique_ptr<DispatcherRebuild> rebuild_;  // a restart's (real time)
  ros::Publisher status_pub_;
  ros::Publisher event_pub_;
  ros::Publisher delete_pub_;
  ros::Publisher answer_pub_;          // lock-step only
  ros::Publisher statist_pub_;         // real time: /flock/position
  ros::Publisher statist_delete_pub_;  // real time: /flock/robot/delete
  ros::Subscriber positions_sub_;
  ros::Subscriber new_sub_;
  ros::Subscriber status_sub_;
  ros::Subscriber progress_sub_;
  ros::ServiceServer submit_srv_;
  ros::ServiceServer signal_srv_;
  ros::ServiceServer status_srv_;
  std::vector<ros::Timer> start_timers_;
  ros::Timer watchdog_timer_;
  ros::WallTimer status_timer_;          // its diagnostic status, once a wall second
  WarnThrottle foreign_report_warning_;  // wall-clock throttles of repeated warnings
  WarnThrottle untracked_warning_;
  std::unique_ptr<NodeDiagnostics> diagnostics_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_MISSION_DISPATCHER_H_
