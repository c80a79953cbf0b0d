// Every shipped missions file (config/missions/*.yaml) parses, and each of its missions is valid
// in the thesis's arena with robots 0..24 and unique ids (what the dispatcher checks at start).
#include <dirent.h>
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "swarm_transport/core/mission.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/dispatcher/dispatcher_options.h"

namespace swarm_transport {
namespace {

std::vector<std::string> MissionsFiles() {
  const std::string dir_name = std::string(ST_CONFIG_DIR) + "/missions";
  std::vector<std::string> files;
  DIR* dir = opendir(dir_name.c_str());
  if (dir == nullptr) return files;
  while (dirent* e = readdir(dir)) {
    const std::string name = e->d_name;
    if (name.size() > 5 && name.substr(name.size() - 5) == ".yaml") {
      files.push_back(dir_name + "/" + name);
    }
  }
  closedir(dir);
  return files;
}

class MissionsFileTest : public ::testing::TestWithParam<std::string> {};

TEST_P(MissionsFileTest, ParsesAndEveryMissionIsValid) {
  XmlRpc::XmlRpcValue file;
  std::string error;
  ASSERT_TRUE(XmlRpcFromYamlFile(GetParam(), &file, &error)) << error;
  std::vector<core::MissionSpec> missions;
  ASSERT_TRUE(MissionsFromXmlRpc(file, &missions, &error)) << error;
  ASSERT_FALSE(missions.empty());
  core::MissionContext context;
  context.world_size_m = SwarmConfig().flocking.world_size_m;
  for (std::uint16_t id = 0; id < 25; ++id) context.known_robots.insert(id);
  std::set<std::uint16_t> ids;
  for (const core::MissionSpec& m : missions) {
    EXPECT_EQ(core::ValidateMission(m, context), "") << GetParam() << " mission " << m.id;
    if (m.id != 0) EXPECT_TRUE(ids.insert(m.id).second) << "id " << m.id << " twice";
  }
}

INSTANTIATE_TEST_SUITE_P(ShippedMissions, MissionsFileTest, ::testing::ValuesIn(MissionsFiles()));

TEST(MissionsFiles, TheThesisTransportAndTwoMissionsShip) { EXPECT_GE(MissionsFiles().size(), 2u); }

TEST(MissionsFiles, AMalformedEntryIsNamed) {
  XmlRpc::XmlRpcValue file;
  file["missions"][0]["id"] = 3;
  file["missions"][0]["robots_from"] = 0;
  file["missions"][0]["robots_to"] = 4;
  file["missions"][0]["leaders"] = 1;
  file["missions"][0]["target"] = 5;  // not a list
  std::vector<core::MissionSpec> missions;
  std::string error;
  EXPECT_FALSE(MissionsFromXmlRpc(file, &missions, &error));
  EXPECT_NE(error.find("target"), std::string::npos) << error;
}

}  // namespace
TEST(MissionsFiles, AtTickIsReadPerMissionAndChecked) {
  XmlRpc::XmlRpcValue file;
  std::string error;
  ASSERT_TRUE(
      XmlRpcFromYamlText("missions:\n"
                         "  - {id: 1, robot_ids: [0], leaders: 1, target: [2, 2], at_tick: 40}\n"
                         "  - {id: 2, robot_ids: [1], leaders: 1, target: [3, 3]}\n",
                         &file, &error))
      << error;
  std::vector<core::MissionSpec> missions;
  std::vector<std::uint64_t> ticks;
  ASSERT_TRUE(MissionsFromXmlRpc(file, &missions, &error, &ticks)) << error;
  EXPECT_EQ(ticks, (std::vector<std::uint64_t>{40, 0}));
  file["missions"][0]["at_tick"] = -1;
  EXPECT_FALSE(MissionsFromXmlRpc(file, &missions, &error, &ticks));
  EXPECT_NE(error.find("missions[0]: 'at_tick'"), std::string::npos) << error;
}

}  // namespace swarm_transport
