// The simulator's mirror of the live missions: what the robots act on, for the radio's mission
// channel, the markers and the rviz status line, and /flock/objects for observers.
#ifndef SWARM_TRANSPORT_ROS_MISSION_MIRROR_H_
#define SWARM_TRANSPORT_ROS_MISSION_MIRROR_H_

#include <ros/ros.h>

#include <cstdint>
#include <string>

#include "swarm_transport/Delete_Object.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/New_Mission.h"
#include "swarm_transport/Tick_Answer.h"
#include "swarm_transport/Update_Object.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/sim/live_mission.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {

// Follows the missions with the robots' rules (core::MayOrder, core::MayReport): orders enter
// validated as the robots validate them, objects move and missions end by their members'
// messages, and each mission's phase is the highest its robots reported. Real time reads the
// /flock/ mission topics; lock-step gets its orders and answers from the session's relay.
class MissionMirror {
 public:
  // `world` must outlive the mirror.
  MissionMirror(core::Admission admission, const sim::World2D* world);

  // Subscribes (real time also to New_Mission) and advertises /flock/objects with `queue`.
  void Connect(ros::NodeHandle nh, bool lockstep, std::uint32_t queue);
  void Shutdown();

  // An order the robots act on from now (invalid ones are ignored, as the robots do).
  void Register(const New_Mission& order);
  // A mission's object moved (an Update_Object taken, or a timed event).
  void UpdateObject(std::uint16_t mission_id, core::Vec2 centre);
  // /flock/objects of tick `tick`, when someone listens.
  void PublishObjects(std::uint64_t tick);

  const sim::LiveMissions& missions() const { return missions_; }
  // For the lock-step engine, which enters the orders it releases and the answers' object
  // updates and deletions itself.
  sim::LiveMissions* mutable_missions() { return &missions_; }

 private:
  void OnMissionNew(const ros::MessageEvent<New_Mission const>& event);
  void OnObjectUpdate(const ros::MessageEvent<Update_Object const>& event);
  void OnObjectDelete(const ros::MessageEvent<Delete_Object const>& event);
  void OnMissionStatus(const ros::MessageEvent<Mission_Status const>& event);
  // core::MayReport against the mirrored mission's members.
  bool MayReport(std::uint16_t mission_id, const std::string& publisher) const;

  core::Admission admission_;
  const sim::World2D* world_;
  sim::LiveMissions missions_;
  ros::Publisher objects_pub_;
  ros::Subscriber mission_new_sub_;
  ros::Subscriber object_update_sub_;
  ros::Subscriber object_delete_sub_;
  ros::Subscriber status_sub_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_MISSION_MIRROR_H_
