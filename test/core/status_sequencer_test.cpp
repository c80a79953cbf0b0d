// The status sequencer (what a robot reports, in which order) and the signal tick.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_agent.h"

namespace swarm_transport {
namespace core {
namespace {

StatusReport Report(std::uint16_t id, MissionPhase phase) {
  StatusReport r;
  r.mission_id = id;
  r.phase = phase;
  return r;
}

std::vector<std::string> Names(const std::vector<StatusReport>& reports) {
  std::vector<std::string> names;
  for (const StatusReport& r : reports) {
    names.push_back(std::to_string(r.mission_id) + ":" + PhaseName(r.phase));
  }
  return names;
}

TEST(StatusSequencerTest, QueuedFirstThenEachPhaseOnceRepeatsAreProgress) {
  StatusSequencer seq;
  seq.Queue(Report(3, MissionPhase::kQueued));
  // Not ready and nothing else to say: the QUEUED waits.
  std::vector<StatusReport> statuses, progress;
  seq.Sequence(false, &statuses, &progress);
  EXPECT_TRUE(statuses.empty());
  // A mission that ends in its first tick: the QUEUED goes out before it even when not ready.
  statuses = {Report(3, MissionPhase::kGathering)};
  seq.Sequence(false, &statuses, &progress);
  EXPECT_EQ(Names(statuses), (std::vector<std::string>{"3:QUEUED", "3:GATHERING"}));
  EXPECT_TRUE(progress.empty());
  // The same phase again is progress; a new phase is a report.
  statuses = {Report(3, MissionPhase::kGathering), Report(3, MissionPhase::kLoading)};
  seq.Sequence(true, &statuses, &progress);
  EXPECT_EQ(Names(statuses), (std::vector<std::string>{"3:LOADING"}));
  EXPECT_EQ(Names(progress), (std::vector<std::string>{"3:GATHERING"}));
  // DONE is the last word: a reused id reports its phases afresh.
  statuses = {Report(3, MissionPhase::kDone)};
  progress.clear();
  seq.Sequence(true, &statuses, &progress);
  EXPECT_EQ(Names(statuses), (std::vector<std::string>{"3:DONE"}));
  statuses = {Report(3, MissionPhase::kLoading)};
  seq.Sequence(true, &statuses, &progress);
  EXPECT_EQ(Names(statuses), (std::vector<std::string>{"3:LOADING"}));
  EXPECT_TRUE(progress.empty());
}

TEST(SignalTickTest, TheDelayRoundsUpToWholeTicks) {
  EXPECT_EQ(SignalTick(65, 2.0, 1.1), 67u);  // 1.82 ticks -> 2
  EXPECT_EQ(SignalTick(65, 2.2, 1.1), 67u);  // exactly 2 ticks (within float error)
  EXPECT_EQ(SignalTick(65, 0.0, 1.1), 65u);
  EXPECT_EQ(SignalTick(10, 2.0, 0.1), 30u);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
