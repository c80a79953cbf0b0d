// What the simulator shows: rviz markers (robots coloured by the swarm they belong to, range
// circles, danger zones, objects, targets, leaders, a line of text with the tick, the swarm
// count and each mission's phase) on /flock/markers and tf world -> robot_<id>/base_link, at most
// markers_rate_hz of wall time. Only publishes: it holds no state of the world.
#ifndef SWARM_TRANSPORT_ROS_VISUALS_H_
#define SWARM_TRANSPORT_ROS_VISUALS_H_

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <cstdint>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/sim/live_mission.h"
#include "swarm_transport/core/geometry.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace sim {

struct VisualsParams {
  double rate_hz = 10.0;         // markers and tf per wall second (0: off)
  bool tf = true;                // broadcast world -> robot_<id>/base_link
  bool range_circles = false;    // draw each robot's local range
  double local_range_m = 1.0;    // the circles' radius
  std::vector<core::Zone> danger_zones;
};

// The markers of the world and its live missions at `tick` (nothing deleted): robots as arrows
// coloured by their swarm (SwarmComponents within local_range_m: one colour per swarm), range
// circles, danger zones, objects, targets, leaders, and the text line "tick T  S swarms
// mission M PHASE ..." above the arena.
visualization_msgs::MarkerArray BuildMarkers(const World2D& world, const LiveMissions& missions,
                                             const VisualsParams& params, ros::Time stamp,
                                             std::uint64_t tick);

class Visuals {
 public:
  Visuals(ros::NodeHandle nh, VisualsParams params);
  // The wall clock the rate counts from (the simulator's Run()).
  void Start(ros::WallTime now);
  // True when a period of wall time has passed since the last true (and the rate is > 0).
  bool Due();
  // Markers (if anybody listens) and tf of the world and its live missions, stamped `stamp`.
  void Publish(const World2D& world, const LiveMissions& missions, ros::Time stamp,
               std::uint64_t tick);
  void Shutdown();
  // The swarms' colours and the range circles follow a live tuning of the local range.
  void SetLocalRange(double local_range_m) { params_.local_range_m = local_range_m; }

 private:
  void PublishMarkers(const World2D& world, const LiveMissions& missions, ros::Time stamp,
                      std::uint64_t tick);
  void PublishTransforms(const World2D& world, ros::Time stamp);

  VisualsParams params_;
  ros::Publisher markers_pub_;
  std::unique_ptr<tf2_ros::TransformBroadcaster> tf_broadcaster_;
  ros::WallTime next_wall_;
  std::set<std::pair<std::string, int>> shown_;  // (ns, id) on screen
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_VISUALS_H_
