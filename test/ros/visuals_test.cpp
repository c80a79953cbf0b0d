// What rviz shows (issue 13): robots coloured by the swarm they belong to, and the status line
// with the tick, the swarm count and each mission's phase.
#include "swarm_transport/ros/simulator/visuals.h"

#include <gtest/gtest.h>

#include <map>
#include <string>

namespace swarm_transport {
namespace sim {
namespace {

using visualization_msgs::Marker;

TEST(VisualsTest, RobotsAreColouredBySwarmAndTheStatusLineNamesTickSwarmsAndPhases) {
  World2D world{WorldParams()};
  std::string error;
  // Two robots 0.6 m apart (one swarm within 1 m), one far away.
  ASSERT_TRUE(world.Spawn(0, {{1.0, 1.0}, core::Angle(0)}, &error)) << error;
  ASSERT_TRUE(world.Spawn(1, {{1.6, 1.0}, core::Angle(0)}, &error)) << error;
  ASSERT_TRUE(world.Spawn(2, {{8.0, 8.0}, core::Angle(0)}, &error)) << error;
  LiveMissions missions;
  LiveMission& m = missions[7];
  m.members = {0, 1};
  m.leaders = {0};
  m.object_position = {1.3, 1.0};
  m.object_size = {1.0, 1.0};
  m.target = {5.0, 5.0};
  m.phase = 3;                      // TRANSPORT
  missions[9].target = {2.0, 9.0};  // a leader-only order, no phase reported yet
  VisualsParams params;
  params.local_range_m = 1.0;
  const visualization_msgs::MarkerArray array =
      BuildMarkers(world, missions, params, ros::Time(1.0), 42);
  std::map<int, Marker> robots;
  const Marker* status = nullptr;
  int objects = 0;
  int leaders = 0;
  for (const Marker& marker : array.markers) {
    if (marker.ns == "robots") robots[marker.id] = marker;
    if (marker.ns == "status") status = &marker;
    if (marker.ns == "objects") ++objects;
    if (marker.ns == "leaders") ++leaders;
  }
  ASSERT_EQ(robots.size(), 3u);
  const auto same = [](const Marker& a, const Marker& b) {
    return a.color.r == b.color.r && a.color.g == b.color.g && a.color.b == b.color.b;
  };
  EXPECT_TRUE(same(robots[0], robots[1]));   // one swarm, one colour
  EXPECT_FALSE(same(robots[0], robots[2]));  // another swarm
  ASSERT_NE(status, nullptr);
  EXPECT_EQ(status->type, Marker::TEXT_VIEW_FACING);
  EXPECT_NE(status->text.find("tick 42"), std::string::npos) << status->text;
  EXPECT_NE(status->text.find("2 swarms"), std::string::npos) << status->text;
  EXPECT_NE(status->text.find("mission 7 TRANSPORT"), std::string::npos) << status->text;
  EXPECT_NE(status->text.find("mission 9 ordered"), std::string::npos) << status->text;
  EXPECT_EQ(objects, 1);  // the leader-only order has none
  EXPECT_EQ(leaders, 1);
}

// A view a person can read: arrows long enough for rviz's default zoom, the arena's border, the
// target with the object's outline and the way there, trails and range circles only when asked
// for, each in the robot's swarm colour.
TEST(VisualsTest, ArrowsAreVisibleTargetsOutlinedAndTrailsAndCirclesOptional) {
  World2D world{WorldParams()};
  std::string error;
  ASSERT_TRUE(world.Spawn(0, {{1.0, 1.0}, core::Angle(90)}, &error)) << error;
  ASSERT_TRUE(world.Spawn(1, {{1.6, 1.0}, core::Angle(0)}, &error)) << error;
  LiveMissions missions;
  LiveMission& m = missions[7];
  m.members = {0, 1};
  m.leaders = {0};
  m.object_position = {1.3, 1.0};
  m.object_size = {1.0, 2.0};
  m.target = {5.0, 5.0};
  VisualsParams params;
  const auto count = [](const visualization_msgs::MarkerArray& a, const std::string& ns) {
    int n = 0;
    for (const Marker& marker : a.markers) n += marker.ns == ns ? 1 : 0;
    return n;
  };
  visualization_msgs::MarkerArray plain = BuildMarkers(world, missions, params, ros::Time(1.0), 3);
  EXPECT_EQ(count(plain, "trails"), 0);
  EXPECT_EQ(count(plain, "ranges"), 0);
  EXPECT_EQ(count(plain, "arena"), 1);
  for (const Marker& marker : plain.markers) {
    if (marker.ns == "robots") {
      EXPECT_GE(marker.scale.x, kArrowMinM);
      EXPECT_GE(marker.scale.x, 3.0 * world.params().robot_radius_m);
    }
    if (marker.ns == "target_outlines") {
      ASSERT_EQ(marker.points.size(), 5u);  // closed rectangle of the object's size
      EXPECT_DOUBLE_EQ(marker.points[0].x, 4.5);
      EXPECT_DOUBLE_EQ(marker.points[0].y, 4.0);
      EXPECT_DOUBLE_EQ(marker.points[2].x, 5.5);
      EXPECT_DOUBLE_EQ(marker.points[2].y, 6.0);
    }
    if (marker.ns == "target_lines") {
      ASSERT_EQ(marker.points.size(), 2u);
      EXPECT_DOUBLE_EQ(marker.points[0].x, 1.3);
      EXPECT_DOUBLE_EQ(marker.points[1].y, 5.0);
    }
  }
  EXPECT_EQ(count(plain, "target_outlines"), 1);
  EXPECT_EQ(count(plain, "target_lines"), 1);

  params.range_circles = true;
  Trails trails;
  trails[0] = {{1.0, 0.8}, {1.0, 0.9}, {1.0, 1.0}};
  trails[1] = {{1.6, 1.0}};  // one point is no line yet
  const visualization_msgs::MarkerArray shown =
      BuildMarkers(world, missions, params, ros::Time(1.0), 3, trails);
  EXPECT_EQ(count(shown, "trails"), 1);
  EXPECT_EQ(count(shown, "ranges"), 2);
  std::map<std::string, Marker> of0;
  for (const Marker& marker : shown.markers) {
    if (marker.id == 0) of0[marker.ns] = marker;
  }
  ASSERT_EQ(of0.count("trails"), 1u);
  EXPECT_EQ(of0["trails"].points.size(), 3u);
  // The trail and the circle wear the robot's swarm colour.
  EXPECT_EQ(of0["trails"].color.r, of0["robots"].color.r);
  EXPECT_EQ(of0["trails"].color.g, of0["robots"].color.g);
  EXPECT_EQ(of0["ranges"].color.b, of0["robots"].color.b);
  EXPECT_DOUBLE_EQ(of0["ranges"].scale.x, 2.0 * params.local_range_m);
}

}  // namespace
}  // namespace sim
}  // namespace swarm_transport
