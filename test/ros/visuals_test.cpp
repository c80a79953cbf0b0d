// What rviz shows (issue 13): robots coloured by the swarm they belong to, and the status line
// with the tick, the swarm count and each mission's phase.
#include "swarm_transport/ros/visuals.h"

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
  m.phase = 3;  // TRANSPORT
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

}  // namespace
}  // namespace sim
}  // namespace swarm_transport
