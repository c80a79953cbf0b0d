// What the simulator shows: rviz markers (the arena's border, robots as arrows coloured by the
// swarm they belong to, optional short trails and local-range circles, danger zones, objects,
// their targets and the way there, leaders, a line of text with the tick, the swarm count and
// each mission's phase) on /flock/markers and tf world -> robot_<id>/base_link, at most
// markers_rate_hz of wall time. It holds no state of the world but the trails' last positions.
#ifndef SWARM_TRANSPORT_ROS_VISUALS_H_
#define SWARM_TRANSPORT_ROS_VISUALS_H_

#include <ros/ros.h>
#include <tf2_ros/transform_broadcaster.h>
#include <visualization_msgs/MarkerArray.h>

#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/sim/live_mission.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace sim {

struct VisualsParams {
  double rate_hz = 10.0;       // markers and tf per wall second (0: off)
  bool tf = true;              // broadcast world -> robot_<id>/base_link
  bool range_circles = false;  // draw each robot's local range, in its swarm's colour
  double local_range_m = 1.0;  // the circles' radius and the swarms' link distance
  int trail_ticks = 0;         // a line through each robot's last positions, ticks (0: off)
  std::vector<core::Zone> danger_zones;
};

// Each robot's positions at its last ticks, oldest first (Visuals::Record).
using Trails = std::map<std::uint16_t, std::deque<core::Vec2>>;

// The markers of the world and its live missions at `tick` (nothing deleted): the arena's
// border, robots as arrows (at least kArrowMinM long, to be seen at rviz's default zoom)
// coloured by their swarm (SwarmComponents within local_range_m: one colour per swarm), their
// trails (with trail_ticks > 0) and range circles (with range_circles), danger zones, objects,
// each target with the object's outline there and a line to it, leaders (a white ring under the
// arrow), and the text line "tick T  S swarms  mission M PHASE ..." above the arena.
visualization_msgs::MarkerArray BuildMarkers(const World2D& world, const LiveMissions& missions,
                                             const VisualsParams& params, ros::Time stamp,
                                             std::uint64_t tick, const Trails& trails = {});
// A robot's arrow is this long at least (m), whatever its radius.
constexpr double kArrowMinM = 0.3;

class Visuals {
 public:
  Visuals(ros::NodeHandle nh, VisualsParams params);
  // The wall clock the rate counts from (the simulator's Run()).
  void Start(ros::WallTime now);
  // Once per tick: each robot's position joins its trail (with trail_ticks > 0).
  void Record(const World2D& world);
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
  Trails trails_;
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_VISUALS_H_
