// The batch engine's inputs and one small run (the rows against launched runs are compared by
// test/experiment.test): job.json reading with clear errors, the rosparam-like merge, and a run
// whose files say what the swarm did.
#include "swarm_transport/ros/engine/batch_run.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "swarm_transport/ros/common/params.h"

namespace swarm_transport {
namespace {

namespace fs = std::filesystem;

class BatchRunTest : public ::testing::Test {
 protected:
  void SetUp() override {
    char pattern[] = "/tmp/st_batch_test_XXXXXX";
    ASSERT_NE(mkdtemp(pattern), nullptr);
    dir_ = pattern;
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string Write(const std::string& name, const std::string& text) {
    const std::string path = dir_ + "/" + name;
    std::ofstream(path) << text;
    return path;
  }

  // A job.json as scripts/experiment writes it, with `extra` members appended.
  std::string Job(const std::string& kind, const std::string& mission,
                  const std::string& extra = "") {
    const std::string config = Write("config.yaml", "cohesion: 0.2\nlocal_range_m: 1.0\n");
    return Write("job.json", "{\"kind\": \"" + kind + "\", \"setting\": \"s\", \"run\": 0, " +
                                 "\"seed\": 3, \"robots\": 6, \"max_ticks\": 50, " +
                                 "\"config_path\": \"" + config + "\", \"run_dir\": \"" + dir_ +
                                 "\", \"record_dir\": \"" + dir_ + "\", \"run_name\": \"r\", " +
                                 "\"placement\": \"random\", \"placement_file\": \"\", " +
                                 "\"trace\": false, \"mission\": " + mission +
                                 ", \"leader_id\": 2" + extra + "}");
  }

  static std::vector<std::string> Lines(const std::string& path) {
    std::ifstream in(path);
    std::vector<std::string> lines;
    for (std::string line; std::getline(in, line);) lines.push_back(line);
    return lines;
  }

  XmlRpc::XmlRpcValue Base() const {
    XmlRpc::XmlRpcValue base;
    std::string error;
    EXPECT_TRUE(XmlRpcFromYamlFile(std::string(ST_CONFIG_DIR) + "/swarm.yaml", &base, &error))
        << error;
    return base;
  }

  std::string dir_;
};

TEST_F(BatchRunTest, ReadsAJobAndNamesWhatIsWrong) {
  BatchJob job;
  std::string error;
  ASSERT_TRUE(ReadBatchJob(Job("leader", "{\"id\": 4, \"target\": [8, 8]}"), &job, &error))
      << error;
  EXPECT_EQ(job.kind, "leader");
  EXPECT_EQ(job.seed, 3);
  EXPECT_EQ(job.max_ticks, 50u);
  ASSERT_TRUE(job.has_mission);
  EXPECT_EQ(job.mission.mission_id, 4);
  EXPECT_EQ(job.mission.robot_index_from, 2);  // the leader only
  EXPECT_EQ(job.mission.robot_index_to, 3);
  EXPECT_EQ(job.mission.leader_number, 1);

  EXPECT_FALSE(ReadBatchJob(Job("dance", "null"), &job, &error));
  EXPECT_NE(error.find("'kind'"), std::string::npos) << error;
  EXPECT_FALSE(ReadBatchJob(Job("transport", "null"), &job, &error));
  EXPECT_NE(error.find("'mission'"), std::string::npos) << error;
  EXPECT_FALSE(ReadBatchJob(Write("bad.json", "{\"kind\": \"flocking\"}"), &job, &error));
  EXPECT_NE(error.find("'setting' is missing"), std::string::npos) << error;
  EXPECT_FALSE(ReadBatchJob(Write("broken.json", "{\"kind\": "), &job, &error));
  EXPECT_NE(error.find("broken.json"), std::string::npos) << error;
  EXPECT_FALSE(ReadBatchJob(dir_ + "/missing.json", &job, &error));
}

TEST_F(BatchRunTest, MergesLikeRosparamLoad) {
  XmlRpc::XmlRpcValue base;
  base["a"] = 1;
  base["d"]["x"] = 1.0;
  base["d"]["y"] = 2.0;
  base["l"][0] = 1;
  XmlRpc::XmlRpcValue over;
  over["a"] = 5;
  over["d"]["y"] = 3.0;
  over["l"][0] = 7;
  over["n"] = std::string("new");
  MergeParams(over, &base);
  EXPECT_EQ(static_cast<int>(base["a"]), 5);
  EXPECT_DOUBLE_EQ(static_cast<double>(base["d"]["x"]), 1.0);  // kept: dictionaries merge
  EXPECT_DOUBLE_EQ(static_cast<double>(base["d"]["y"]), 3.0);
  EXPECT_EQ(base["l"].size(), 1);  // lists are replaced
  EXPECT_EQ(static_cast<int>(base["l"][0]), 7);
  EXPECT_EQ(static_cast<std::string>(base["n"]), "new");
}

TEST_F(BatchRunTest, AFlockingRunWritesItsSamplesAndSummary) {
  BatchJob job;
  std::string error;
  ASSERT_TRUE(ReadBatchJob(Job("flocking", "null"), &job, &error)) << error;
  ASSERT_TRUE(RunBatchJob(job, Base(), &error)) << error;
  // Ticks 0..50 at the config's tick period: a sample every 10 s of sim time from tick 0.
  const std::vector<std::string> samples = Lines(dir_ + "/r/swarm_count.csv");
  ASSERT_GE(samples.size(), 2u);
  EXPECT_EQ(samples[0], "tick,sim_time_s,robots,swarm_count,largest_swarm");
  EXPECT_EQ(samples[1].substr(0, 4), "0,0,");
  const std::vector<std::string> run = Lines(dir_ + "/r/run.csv");
  ASSERT_EQ(run.size(), 2u);
  EXPECT_EQ(run[1].substr(0, 11), "r,3,6,50,5,");  // name, seed, robots, ticks, sim time
  std::ifstream result(dir_ + "/result.json");
  std::stringstream text;
  text << result.rdbuf();
  EXPECT_NE(text.str().find("\"status\": \"ok\""), std::string::npos) << text.str();
  EXPECT_NE(text.str().find("\"end\": \"max_ticks\""), std::string::npos) << text.str();
}

TEST_F(BatchRunTest, AMissionTheDispatcherWouldRejectFailsTheRunWithItsReason) {
  BatchJob job;
  std::string error;
  // Robot 40 does not exist in a swarm of 6.
  ASSERT_TRUE(ReadBatchJob(Job("transport",
                               "{\"id\": 7, \"target\": [3, 3], \"leaders\": 1, \"group\": 41, "
                               "\"object\": [7, 7, 2, 2]}"),
                           &job, &error))
      << error;
  EXPECT_FALSE(RunBatchJob(job, Base(), &error));
  EXPECT_NE(error.find("the dispatcher rejected the mission"), std::string::npos) << error;
  std::ifstream result(dir_ + "/result.json");
  std::stringstream text;
  text << result.rdbuf();
  EXPECT_NE(text.str().find("\"status\": \"error\""), std::string::npos) << text.str();
}

}  // namespace
}  // namespace swarm_transport
