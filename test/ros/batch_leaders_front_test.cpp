// (issue 27, item 6) Leaders chosen by plan lead from the front: a count-only order (the
// dispatcher picks the robots and names as leaders those whose slots lie furthest toward the
// target) in a batch run of 25 robots; when the transport starts no non-leader stands ahead of
// the rearmost leader (result.json's leaders_behind, GatheringMetrics::LeadersBehind). Before
// planned gathering became the default for such orders (hold: the robots stood where they
// entered the object) robot_choice's seed 1 had one robot ahead of a leader.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/engine/batch_run.h"

namespace swarm_transport {
namespace {

namespace fs = std::filesystem;

std::string RunCountOnly(const std::string& dir, int seed, const std::string& mission) {
  const std::string job_path = dir + "/job.json";
  std::ofstream(job_path) << "{\"kind\": \"transport\", \"setting\": \"s\", \"run\": 0, "
                          << "\"seed\": " << seed << ", \"robots\": 25, \"max_ticks\": 400, "
                          << "\"config_path\": \"" << ST_CONFIG_DIR << "/thesis_transport.yaml\", "
                          << "\"run_dir\": \"" << dir << "\", \"record_dir\": \"" << dir
                          << "\", \"run_name\": \"r\", \"placement\": \"random\", "
                          << "\"placement_file\": \"\", \"trace\": false, \"mission\": " << mission
                          << ", \"leader_id\": null}";
  BatchJob job;
  std::string error;
  EXPECT_TRUE(ReadBatchJob(job_path, &job, &error)) << error;
  XmlRpc::XmlRpcValue base;
  EXPECT_TRUE(XmlRpcFromYamlFile(std::string(ST_CONFIG_DIR) + "/swarm.yaml", &base, &error))
      << error;
  EXPECT_TRUE(RunBatchJob(job, base, &error)) << error;
  std::ifstream in(dir + "/result.json");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

TEST(BatchLeadersFrontTest, LeadersChosenByPlanStandAtTheFrontWhenTheTransportStarts) {
  char pattern[] = "/tmp/st_front_test_XXXXXX";
  ASSERT_NE(mkdtemp(pattern), nullptr);
  const std::string dir = pattern;
  const std::string count =
      "{\"id\": 7, \"target\": [3, 3], \"leaders\": 2, \"count\": 10, \"object\": [7, 7, 2, 2]}";
  const std::string result = RunCountOnly(dir, 1, count);
  EXPECT_NE(result.find("\"end\": \"DONE\""), std::string::npos) << result;
  EXPECT_NE(result.find("\"leaders_behind\": 0.0"), std::string::npos) << result;
  // The check can fail: robots 0-9 with leaders 0 and 1 (a range) do not lead from the front.
  const std::string range =
      "{\"id\": 7, \"target\": [3, 3], \"leaders\": 2, \"group\": 10, \"object\": [7, 7, 2, 2]}";
  const std::string ranged = RunCountOnly(dir, 1, range);
  EXPECT_NE(ranged.find("\"leaders_behind\": "), std::string::npos) << ranged;
  EXPECT_EQ(ranged.find("\"leaders_behind\": 0.0"), std::string::npos) << ranged;
  fs::remove_all(dir);
}

}  // namespace
}  // namespace swarm_transport
