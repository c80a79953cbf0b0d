// Every shipped config/*.yaml loads and validates; broken configurations are rejected with a
// message naming the key (like cartographer_ros configuration_files_test).
#include <dirent.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "swarm_transport/ros/common/params.h"

namespace swarm_transport {
namespace {

std::vector<std::string> ConfigFiles() {
  std::vector<std::string> files;
  DIR* dir = opendir(ST_CONFIG_DIR);
  if (dir == nullptr) return files;
  while (dirent* e = readdir(dir)) {
    const std::string name = e->d_name;
    if (name.size() > 5 && name.substr(name.size() - 5) == ".yaml") {
      files.push_back(std::string(ST_CONFIG_DIR) + "/" + name);
    }
  }
  closedir(dir);
  return files;
}

class ConfigFileTest : public ::testing::TestWithParam<std::string> {};

TEST_P(ConfigFileTest, LoadsAndValidates) {
  XmlRpc::XmlRpcValue dict;
  std::string error;
  ASSERT_TRUE(XmlRpcFromYamlFile(GetParam(), &dict, &error)) << error;
  SwarmConfig config;
  EXPECT_TRUE(ConfigFromXmlRpc(dict, &config, &error)) << GetParam() << ": " << error;
  EXPECT_EQ(config.Validate(), "");
}

INSTANTIATE_TEST_SUITE_P(ShippedConfigs, ConfigFileTest, ::testing::ValuesIn(ConfigFiles()));

TEST(ConfigFiles, AtLeastTheDefaultAndThesisPresetsShip) {
  const std::vector<std::string> files = ConfigFiles();
  EXPECT_GE(files.size(), 4u);
}

TEST(ConfigFiles, DefaultHasTheThesisGeometry) {
  XmlRpc::XmlRpcValue dict;
  std::string error;
  ASSERT_TRUE(XmlRpcFromYamlFile(std::string(ST_CONFIG_DIR) + "/swarm.yaml", &dict, &error));
  SwarmConfig config;
  ASSERT_TRUE(ConfigFromXmlRpc(dict, &config, &error)) << error;
  EXPECT_DOUBLE_EQ(config.flocking.world_size_m, 11.088889);
  EXPECT_DOUBLE_EQ(config.leader.goal_tolerance_m, 0.05);
}

TEST(ConfigFiles, ObstaclesGiveTwoZones) {
  XmlRpc::XmlRpcValue dict;
  std::string error;
  ASSERT_TRUE(XmlRpcFromYamlFile(std::string(ST_CONFIG_DIR) + "/obstacles.yaml", &dict, &error));
  SwarmConfig config;
  ASSERT_TRUE(ConfigFromXmlRpc(dict, &config, &error)) << error;
  ASSERT_EQ(config.danger_zones.size(), 2u);
  EXPECT_TRUE(config.danger_zones[0].Forbids({5.5, 5.5}));
  EXPECT_FALSE(config.danger_zones[0].Forbids({1.0, 1.0}));
  EXPECT_TRUE(config.danger_zones[1].Forbids({2.5, 8.0}));
}

XmlRpc::XmlRpcValue Dict(const char* key, XmlRpc::XmlRpcValue value) {
  XmlRpc::XmlRpcValue d;
  d[key] = value;
  return d;
}

TEST(ConfigValidation, RejectsBadValuesAndKeepsTheOldConfig) {
  struct Case {
    const char* key;
    XmlRpc::XmlRpcValue value;
  };
  const std::vector<Case> cases = {
      {"local_range_m", XmlRpc::XmlRpcValue(-1.0)},
      {"speed_m_per_tick", XmlRpc::XmlRpcValue(std::nan(""))},
      {"free_will_deg", XmlRpc::XmlRpcValue(400.0)},
      {"cohesion", XmlRpc::XmlRpcValue(1.5)},
      {"robot_radius_m", XmlRpc::XmlRpcValue(0.0)},
      {"tick_period_s", XmlRpc::XmlRpcValue(0.0)},
      {"seed", XmlRpc::XmlRpcValue(-3)},
      {"chain_hops", XmlRpc::XmlRpcValue(0)},
      {"neighbourhood", XmlRpc::XmlRpcValue(std::string("ring"))},
      {"gathering", XmlRpc::XmlRpcValue(1)},
      {"gather_planner", XmlRpc::XmlRpcValue(std::string("closest"))},
      {"replan_period", XmlRpc::XmlRpcValue(0)},
      {"planner_turn_deg_per_tick", XmlRpc::XmlRpcValue(0.0)},
      {"leaders_bound", XmlRpc::XmlRpcValue(std::string("yes"))},
      {"formation_speed_fraction", XmlRpc::XmlRpcValue(1.5)},
      {"standby", XmlRpc::XmlRpcValue(std::string("spread"))},
      {"balloon_growth_m_per_tick", XmlRpc::XmlRpcValue(0.0)},
      {"loading_spread", XmlRpc::XmlRpcValue(std::string("flock"))},
      {"loading_spread_ticks", XmlRpc::XmlRpcValue(0)},
      {"local_range_m", XmlRpc::XmlRpcValue(std::string("far"))},
  };
  for (Case c : cases) {
    XmlRpc::XmlRpcValue d = Dict(c.key, c.value);
    SwarmConfig config;
    const double range_before = config.flocking.local_range_m;
    std::string error;
    EXPECT_FALSE(ConfigFromXmlRpc(d, &config, &error)) << c.key;
    EXPECT_NE(error.find(c.key), std::string::npos) << "message '" << error << "' names no key";
    EXPECT_DOUBLE_EQ(config.flocking.local_range_m, range_before);
  }
}

TEST(ConfigValidation, StandbyBalloonIsReadWithItsGrowth) {
  XmlRpc::XmlRpcValue d = Dict("standby", XmlRpc::XmlRpcValue(std::string("balloon")));
  d["balloon_growth_m_per_tick"] = XmlRpc::XmlRpcValue(0.05);
  SwarmConfig config;
  EXPECT_EQ(config.standby, swarm_transport::core::StandbyMode::kFlock);
  std::string error;
  ASSERT_TRUE(ConfigFromXmlRpc(d, &config, &error)) << error;
  EXPECT_EQ(config.standby, swarm_transport::core::StandbyMode::kBalloon);
  EXPECT_DOUBLE_EQ(config.balloon.growth_m_per_tick, 0.05);
}

TEST(ConfigValidation, LoadingSpreadIsReadWithItsTicks) {
  XmlRpc::XmlRpcValue d = Dict("loading_spread", XmlRpc::XmlRpcValue(std::string("balloon")));
  d["loading_spread_ticks"] = XmlRpc::XmlRpcValue(12);
  SwarmConfig config;
  EXPECT_EQ(config.loading_spread, swarm_transport::core::LoadingSpread::kNone);
  std::string error;
  ASSERT_TRUE(ConfigFromXmlRpc(d, &config, &error)) << error;
  EXPECT_EQ(config.loading_spread, swarm_transport::core::LoadingSpread::kBalloon);
  EXPECT_EQ(config.loading_spread_ticks, 12);
}

// A leader key read as a bool: its default, the other value taken, and a string or a number in
// its place refused with the key named and the config left as it was.
void ExpectLeaderBool(const char* key, bool core::LeaderParams::*member, bool by_default) {
  SwarmConfig config;
  EXPECT_EQ(config.leader.*member, by_default) << key;
  std::string error;
  XmlRpc::XmlRpcValue other = Dict(key, XmlRpc::XmlRpcValue(!by_default));
  ASSERT_TRUE(ConfigFromXmlRpc(other, &config, &error)) << error;
  EXPECT_EQ(config.leader.*member, !by_default) << key;
  for (const XmlRpc::XmlRpcValue& value :
       {XmlRpc::XmlRpcValue(std::string("yes")), XmlRpc::XmlRpcValue(1.5)}) {
    XmlRpc::XmlRpcValue bad = Dict(key, value);
    EXPECT_FALSE(ConfigFromXmlRpc(bad, &config, &error)) << key;
    EXPECT_NE(error.find(key), std::string::npos) << error;
    EXPECT_EQ(config.leader.*member, !by_default) << key;  // unchanged by the refused dict
  }
}

TEST(ConfigValidation, LeaderWaitEvaluatedAnglesIsReadAsABool) {
  ExpectLeaderBool("leader_wait_evaluated_angles", &core::LeaderParams::wait_evaluated_angles,
                   false);
}

TEST(ConfigValidation, LeaderGiveUpBeyondRangeIsReadAsABool) {
  ExpectLeaderBool("leader_give_up_beyond_range", &core::LeaderParams::give_up_beyond_range, false);
}

TEST(ConfigValidation, LeaderCentroidWithSelfIsReadAsABool) {
  ExpectLeaderBool("leader_centroid_with_self", &core::LeaderParams::centroid_with_self, false);
}

TEST(ConfigValidation, LeaderCheckCollisionsIsReadAsABool) {
  ExpectLeaderBool("leader_check_collisions", &core::LeaderParams::check_collisions, true);
}

TEST(ConfigValidation, IntegersAreAcceptedWhereNumbersAreExpected) {
  XmlRpc::XmlRpcValue d = Dict("free_will_deg", XmlRpc::XmlRpcValue(45));
  SwarmConfig config;
  std::string error;
  ASSERT_TRUE(ConfigFromXmlRpc(d, &config, &error)) << error;
  EXPECT_DOUBLE_EQ(config.flocking.free_will_deg, 45.0);
}

TEST(ConfigValidation, RejectsBadZones) {
  XmlRpc::XmlRpcValue zone;
  zone["shape"] = std::string("rect");
  zone["x"] = 1.0;
  zone["y"] = 1.0;
  zone["size_x"] = -2.0;
  zone["size_y"] = 1.0;
  XmlRpc::XmlRpcValue zones;
  zones.setSize(1);
  zones[0] = zone;
  XmlRpc::XmlRpcValue d = Dict("danger_zones", zones);
  SwarmConfig config;
  std::string error;
  EXPECT_FALSE(ConfigFromXmlRpc(d, &config, &error));
  EXPECT_NE(error.find("danger_zones[0]"), std::string::npos) << error;
}

}  // namespace
}  // namespace swarm_transport
