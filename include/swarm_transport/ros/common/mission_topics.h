// The swarm-wide mission topics (/flock/mission/new, /flock/object/update and /delete,
// /flock/freeze, /flock/continue, /flock/mission/event, /flock/mission/status and, out only,
// /flock/mission/progress) as a robot hears and, as a real-time first leader, speaks them. The
// one place a robot's side names each kind of mission message: a robot process subscribes them
// for itself, a host of many robots once for all of them, and both get core::MissionMessage.
// Lock-step robots need neither: their rounds carry what the relay passed on, their answers
// what they say.
#ifndef SWARM_TRANSPORT_ROS_MISSION_TOPICS_H_
#define SWARM_TRANSPORT_ROS_MISSION_TOPICS_H_

#include <ros/ros.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "swarm_transport/Tick_Answer.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/ros/common/graph.h"

namespace swarm_transport {

// Subscribes every mission topic a robot hears; each message arrives converted, with its sender
// (its publisher), on the node handle's callback queue.
class MissionTopics {
 public:
  using Take = std::function<void(const core::MissionMessage&, const core::Sender&)>;
  void Subscribe(ros::NodeHandle nh, Take take);
  // Stops every subscription (each waits for its callback in progress).
  void Shutdown();

 private:
  template <typename M>
  void Add(ros::NodeHandle& nh, const char* topic, std::uint32_t queue_size);
  Take take_;
  std::vector<ros::Subscriber> subs_;
};

// A real-time first leader's publishers of the mission topics: only robots that became one
// advertise them, so the swarm does not become all-to-all.
class MissionPublishers {
 public:
  bool advertised() const { return static_cast<bool>(status_pub_); }
  // Advertises them (once) and asks the master how many nodes subscribe to each.
  void Advertise(ros::NodeHandle nh);
  // True when every robot can hear them (or none are advertised): a message published before a
  // subscriber connected is lost for it, so a first leader holds its phase machine until every
  // node that subscribed when it got the mission is connected, or 5 s of wall time passed.
  bool Ready();
  // Publishes an answer's mission messages (statuses on /flock/mission/status, progress on
  // .../progress, ...). False when it has some but the publishers are not advertised.
  bool Publish(const Tick_Answer& answer);

 private:
  ros::Publisher freeze_pub_;
  ros::Publisher continue_pub_;
  ros::Publisher update_pub_;
  ros::Publisher delete_pub_;
  ros::Publisher status_pub_;
  // Progress within a phase (not relayed, not counted for the lock-step barrier).
  ros::Publisher progress_pub_;
  TopicNodeCounts expected_;  // the graph when they were advertised
  ros::WallTime since_;
  bool ready_ = false;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_MISSION_TOPICS_H_
