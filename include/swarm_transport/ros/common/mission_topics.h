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

#include "swarm_transport/Mission_Status.h"
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
  // The same with the publisher's node name and, for an order, its start tick (0 for the
  // others): a lock-step relay orders by publisher and holds an order until its tick. Every
  // topic gets `queue_size`.
  using TakeFrom = std::function<void(const core::MissionMessage&, const std::string& publisher,
                                      std::uint64_t start_tick)>;
  void SubscribeFrom(ros::NodeHandle nh, TakeFrom take, std::uint32_t queue_size);
  // Stops every subscription (each waits for its callback in progress).
  void Shutdown();
  // Every publisher the master lists for each topic is connected; with `only`, for those
  // topics only (e.g. the dispatcher's: names::kMissionNew and names::kMissionEvent).
  bool AllConnected(const TopicNodeCounts& graph, const std::vector<std::string>& only = {}) const;

 private:
  template <typename M>
  void Add(ros::NodeHandle& nh, const char* topic, std::uint32_t queue_size);
  void AddAll(ros::NodeHandle& nh, std::uint32_t queue_size);
  TakeFrom take_;
  std::vector<ros::Subscriber> subs_;
};

// A real-time robot's publishers of the mission topics (a simulated robot process advertises
// them at start-up, a robot host or a robot on hardware when one of its robots first leads),
// and a lock-step simulator's, which publishes its robots' answers on them for observers.
class MissionPublishers {
 public:
  bool advertised() const { return static_cast<bool>(status_pub_); }
  // Advertises them (once) and asks the master how many nodes subscribe to each; `queue_size`
  // 0: each topic's own.
  void Advertise(ros::NodeHandle nh, std::uint32_t queue_size = 0);
  // True when every robot can hear them (or none are advertised): a message published before a
  // subscriber connected is lost for it, so a first leader holds its phase machine until every
  // node that subscribed when it got the mission is connected, or 5 s of wall time passed.
  bool Ready();
  // Publishes an answer's mission messages (statuses on /flock/mission/status, progress on
  // .../progress, ...). False when it has some but the publishers are not advertised.
  bool Publish(const Tick_Answer& answer);
  // One mission message on its topic (object update and delete, freeze, continue; the others
  // are the dispatcher's topics and are not published here), one status or progress report.
  void Publish(const core::MissionMessage& message);
  void PublishStatus(const Mission_Status& status) { status_pub_.publish(status); }
  void PublishProgress(const Mission_Status& status) { progress_pub_.publish(status); }
  // Every subscriber the master lists for each topic is connected.
  bool AllConnected(const TopicNodeCounts& graph) const;

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
