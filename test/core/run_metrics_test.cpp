// RunMetrics [SPEC 8]: the recorder's sampling grid, mission phases, windows and rows, fed
// hand-built frames, orders and statuses.
#include "swarm_transport/core/run_metrics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <optional>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "fixtures.h"

namespace swarm_transport {
namespace core {
namespace {

using Robots = std::vector<std::pair<std::uint16_t, Vec2>>;

// Tick period 0.1 s of sim time, as the thesis's swarm.
constexpr double kTickS = 0.1;

// A frame of robots given in ascending id order.
MetricsFrame Frame(std::uint64_t tick, const Robots& robots) {
  MetricsFrame frame;
  frame.tick = tick;
  frame.sim_time_s = static_cast<double>(tick) * kTickS;
  for (const auto& r : robots) {
    frame.ids.push_back(r.first);
    frame.positions.push_back(r.second);
  }
  return frame;
}

// What a RunMetrics logged, "I " / "W " + text.
struct LogLines {
  std::vector<std::string> lines;
  RunMetrics::Log Log() {
    return [this](RunMetrics::Level level, const std::string& text) {
      lines.push_back((level == RunMetrics::Level::kWarn ? "W " : "I ") + text);
    };
  }
  bool Has(const std::string& line) const {
    for (const auto& l : lines) {
      if (l == line) return true;
    }
    return false;
  }
};

RunMetricsParams Params(double sample_period_s = 1000.0) {
  RunMetricsParams p;
  p.local_range_m = 1.0;
  p.goal_tolerance_m = 0.15;
  p.sample_period_s = sample_period_s;
  return p;
}

// Field `index` of a CSV row.
std::string Field(const std::string& row, std::size_t index) {
  std::istringstream in(row);
  std::string field;
  for (std::size_t i = 0; i <= index; ++i) std::getline(in, field, ',');
  return field;
}

// The thesis fixture's robots 0 (leader), 1 and 2 in a row along x at tick `tick`, all moving
// +0.125 m per tick (exact in binary): robot 1 is 0.5 m from the leader (contact), robot 2
// 1.5 m (none).
Robots Carriers(std::uint64_t tick) {
  const double x = 1.0 + 0.125 * static_cast<double>(tick);
  return {{0, {x, 1.0}}, {1, {x + 0.5, 1.0}}, {2, {x + 1.5, 1.0}}};
}

TEST(RunMetricsTest, IndexOfFindsIdsInAFrame) {
  const MetricsFrame frame = Frame(0, {{2, {1.0, 1.0}}, {5, {2.0, 2.0}}, {9, {3.0, 3.0}}});
  EXPECT_EQ(frame.IndexOf(2), 0);
  EXPECT_EQ(frame.IndexOf(9), 2);
  EXPECT_EQ(frame.IndexOf(4), -1);
  EXPECT_EQ(frame.IndexOf(10), -1);
  EXPECT_EQ(MetricsFrame().IndexOf(0), -1);
}

TEST(RunMetricsTest, HistoryCapacityHoldsAFixedNumberOfPositionsWithinBounds) {
  EXPECT_EQ(RunMetrics::HistoryCapacity(0), 20000u);
  EXPECT_EQ(RunMetrics::HistoryCapacity(200), 20000u);
  EXPECT_EQ(RunMetrics::HistoryCapacity(400), 10000u);
  EXPECT_EQ(RunMetrics::HistoryCapacity(16000), 256u);
  EXPECT_EQ(RunMetrics::HistoryCapacity(1000000), 256u);
}

TEST(RunMetricsTest, SamplesFollowTheGridFromTheFirstFrameAndAJumpSkipsMissedTimes) {
  RunMetrics metrics(Params(1.0));
  std::vector<std::uint64_t> sampled;
  std::optional<SwarmSample> first;
  // Robots 0 and 1 together, robot 2 apart: 2 swarms, the largest of 2.
  const Robots robots = {{0, {1.0, 1.0}}, {1, {1.5, 1.0}}, {2, {5.0, 5.0}}};
  for (std::uint64_t tick : {5, 6, 10, 14, 15, 16, 24, 25, 38, 44, 45}) {
    std::optional<SwarmSample> sample;
    ASSERT_TRUE(metrics.AddFrame(Frame(tick, robots), &sample));
    if (sample) sampled.push_back(sample->tick);
    if (sample && !first) first = sample;
  }
  // The first frame (0.5 s), then 1.5 s, 2.5 s (not 2.4 s); the jump to 3.8 s skips 3.5 s
  // and the next is due at 4.5 s, not 4.8 s.
  EXPECT_EQ(sampled, (std::vector<std::uint64_t>{5, 15, 25, 38, 45}));
  EXPECT_EQ(metrics.samples(), 5u);
  ASSERT_TRUE(first.has_value());
  EXPECT_EQ(first->tick, 5u);
  EXPECT_DOUBLE_EQ(first->sim_time_s, 0.5);
  EXPECT_EQ(first->robots, 3u);
  EXPECT_EQ(first->swarm_count, 2u);
  EXPECT_EQ(first->largest_swarm, 2u);
  EXPECT_EQ(first->live_missions, 0u);
  EXPECT_EQ(RunMetrics::SwarmRow(*first), "5,0.5,3,2,2");
  // A frame not after the newest changes nothing.
  std::optional<SwarmSample> sample;
  EXPECT_FALSE(metrics.AddFrame(Frame(45, robots), &sample));
  EXPECT_FALSE(metrics.AddFrame(Frame(30, robots), &sample));
  EXPECT_FALSE(sample.has_value());
  EXPECT_EQ(metrics.newest_tick(), 45u);
}

TEST(RunMetricsTest, SampleTimesWithinEpsilonOfTheirDueTimeAreDue) {
  // From tick 23 (2.3 s) the grid puts 4.3 s at 2.3 + 2 * 1.0 = 4.300000000000001, while tick
  // 43 is at 43 * 0.1 = 4.3: due all the same, not one tick late.
  RunMetrics metrics(Params(1.0));
  std::vector<std::uint64_t> sampled;
  for (std::uint64_t tick = 23; tick <= 53; ++tick) {
    std::optional<SwarmSample> sample;
    metrics.AddFrame(Frame(tick, {{0, {1.0, 1.0}}}), &sample);
    if (sample) sampled.push_back(sample->tick);
  }
  EXPECT_EQ(sampled, (std::vector<std::uint64_t>{23, 33, 43, 53}));
}

TEST(RunMetricsTest, SampleCountsLiveMissions) {
  RunMetrics metrics(Params(1.0));
  EXPECT_EQ(metrics.AddOrder(fixtures::Thesis(7), 0), "");
  EXPECT_EQ(metrics.AddStatus(9, MissionPhase::kQueued, 0, {}), "");
  std::optional<SwarmSample> sample;
  ASSERT_TRUE(metrics.AddFrame(Frame(0, Carriers(0)), &sample));
  ASSERT_TRUE(sample.has_value());
  EXPECT_EQ(sample->live_missions, 2u);
}

TEST(RunMetricsTest, TransportRowHasItsPhasesAndItsWindowEndsAtTheUnloadingTick) {
  LogLines log;
  RunMetrics metrics(Params(), log.Log());
  EXPECT_EQ(metrics.AddOrder(fixtures::Thesis(7), 0), "");
  // Frames up to tick 12 come first; the leader's statuses of ticks 0..9 only afterwards.
  for (std::uint64_t tick = 0; tick <= 12; ++tick) {
    ASSERT_TRUE(metrics.AddFrame(Frame(tick, Carriers(tick)), nullptr));
  }
  EXPECT_EQ(metrics.AddStatus(7, MissionPhase::kQueued, 0, {7.0, 7.0}), "");
  EXPECT_EQ(metrics.AddStatus(7, MissionPhase::kGathering, 2, {7.0, 7.0}), "");
  EXPECT_EQ(metrics.AddStatus(7, MissionPhase::kLoading, 4, {7.0, 7.0}), "");
  EXPECT_EQ(metrics.AddStatus(7, MissionPhase::kTransport, 5, {7.0, 7.0}), "");
  EXPECT_EQ(metrics.AddStatus(7, MissionPhase::kUnloading, 8, {3.0, 3.05}), "");
  EXPECT_TRUE(metrics.TakeMissionRows().empty());  // not DONE yet
  EXPECT_EQ(metrics.missions_unfinished(), 1u);
  EXPECT_EQ(metrics.AddStatus(7, MissionPhase::kDone, 9, {3.0, 3.04}), "");
  const std::vector<std::string> rows = metrics.TakeMissionRows();
  // Fed ticks 5..8 (not up to 12): 3 ticks of 0.125 m for every robot, no slip, no leader
  // wait; robot 1 always in the leader's range, robot 2 never; the object 0.04 m off.
  const std::string row = "7,transport,3,1,DONE,0,2,4,5,8,9,3,0,0.375,0,,,0.04,0.5,0.353553391";
  ASSERT_EQ(rows, std::vector<std::string>{row});
  EXPECT_TRUE(log.Has("I mission 7 DONE: " + row));
  EXPECT_TRUE(metrics.TakeMissionRows().empty());
  EXPECT_EQ(metrics.missions_done(), 1u);
  EXPECT_EQ(metrics.missions_aborted(), 0u);
  EXPECT_EQ(metrics.missions_unfinished(), 0u);
}

TEST(RunMetricsTest, TransportMissingARobotIsWarnedOnceAndItsTicksAreSkipped) {
  LogLines log;
  RunMetrics metrics(Params(), log.Log());
  metrics.AddOrder(fixtures::Thesis(7), 0);
  metrics.AddStatus(7, MissionPhase::kTransport, 0, {7.0, 7.0});
  for (std::uint64_t tick = 0; tick <= 6; ++tick) {
    Robots robots = Carriers(tick);
    if (tick == 3 || tick == 4) robots.pop_back();  // robot 2 missing
    metrics.AddFrame(Frame(tick, robots), nullptr);
  }
  metrics.AddStatus(7, MissionPhase::kAborted, 6, {5.0, 5.0});
  const std::vector<std::string> rows = metrics.TakeMissionRows();
  ASSERT_EQ(rows.size(), 1u);
  // Ticks 0..6 without 3 and 4: the tracker spans 0..6 all the same.
  EXPECT_EQ(Field(rows[0], 4), "ABORTED");
  EXPECT_EQ(Field(rows[0], 11), "6");
  EXPECT_EQ(log.lines, (std::vector<std::string>{
                           "W mission 7: a robot of the mission is missing from /flock/world_poses "
                           "at tick 3; such ticks are skipped",
                           "I mission 7 ABORTED: " + rows[0]}));
  EXPECT_EQ(metrics.missions_aborted(), 1u);
}

// Robot 4 drives alone to (5, 5), 0.1 m per tick from (5, 4.5); robot 5 follows 0.3 m behind.
MissionSpec LeaderOnly(std::uint16_t id) {
  MissionSpec m;
  m.id = id;
  m.range_from = 4;
  m.range_to = 5;
  m.leader_number = 1;
  m.target = {5.0, 5.0};
  return m;
}
Robots Driving(std::uint64_t tick) {
  const double y = 4.5 + 0.1 * static_cast<double>(tick);
  return {{4, {5.0, y}}, {5, {5.0, y - 0.3}}};
}

TEST(RunMetricsTest, LeaderOnlyArrivalWithinGoalToleranceIsDoneWithoutADoneStatus) {
  LogLines log;
  RunMetrics metrics(Params(), log.Log());
  EXPECT_EQ(metrics.AddOrder(LeaderOnly(8), 0), "");
  metrics.AddStatus(8, MissionPhase::kQueued, 0, {5.0, 4.5});
  // Its window's end is not known: the frames wait (for a DONE, the history or the end).
  for (std::uint64_t tick = 0; tick <= 7; ++tick) {
    metrics.AddFrame(Frame(tick, Driving(tick)), nullptr);
  }
  EXPECT_TRUE(metrics.TakeMissionRows().empty());
  EXPECT_EQ(metrics.missions_unfinished(), 1u);
  // Fed at the end: 0.2 m off at tick 3, 0.1 m at tick 4 - arrived; ticks 5..7 (beyond the
  // target) are not its.
  metrics.Drain();
  const std::string row = "8,leader,1,1,DONE,0,,,,,4,,,,0,1,1,0.1,,";
  EXPECT_EQ(metrics.TakeMissionRows(), std::vector<std::string>{row});
  EXPECT_EQ(log.lines, (std::vector<std::string>{
                           "I mission 8: leader 4 within 0.150 m of its target at tick 4: done",
                           "I mission 8 DONE: " + row}));
  // Its DONE, late: news of a written mission.
  EXPECT_EQ(metrics.AddStatus(8, MissionPhase::kDone, 5, {5.0, 5.0}), "");
  EXPECT_TRUE(metrics.TakeMissionRows().empty());
  EXPECT_EQ(metrics.missions_done(), 1u);
  EXPECT_EQ(metrics.missions_unfinished(), 0u);
}

TEST(RunMetricsTest, LeaderOnlyArrivalCutsTheWindowOfAnAbortedMission) {
  RunMetrics metrics(Params());
  metrics.AddOrder(LeaderOnly(8), 0);
  for (std::uint64_t tick = 0; tick <= 7; ++tick) {
    metrics.AddFrame(Frame(tick, Driving(tick)), nullptr);
  }
  // A GATHERING does not end a leader-only window; an ABORTED of tick 7 does, and the frames
  // it lets in show the arrival at tick 4, which cuts the window there: the leader is 0.1 m
  // off (0.2 m at tick 7), and the mission stays ABORTED.
  metrics.AddStatus(8, MissionPhase::kGathering, 6, {5.0, 5.0});
  EXPECT_TRUE(metrics.TakeMissionRows().empty());
  metrics.AddStatus(8, MissionPhase::kAborted, 7, {5.0, 5.0});
  EXPECT_EQ(metrics.TakeMissionRows(),
            std::vector<std::string>{"8,leader,1,1,ABORTED,,6,,,,,,,,0,,,0.1,,"});
  EXPECT_EQ(metrics.missions_done(), 0u);
  EXPECT_EQ(metrics.missions_aborted(), 1u);
}

TEST(RunMetricsTest, RejectedOfANeverAcceptedMissionIsForgottenButNotOfAnAcceptedOne) {
  RunMetrics metrics(Params());
  metrics.AddOrder(fixtures::Thesis(3), 0);
  metrics.AddOrder(fixtures::Thesis(4), 0);
  metrics.AddStatus(4, MissionPhase::kQueued, 0, {7.0, 7.0});
  EXPECT_EQ(metrics.missions_unfinished(), 2u);
  EXPECT_EQ(metrics.AddStatus(3, MissionPhase::kRejected, 0, {}), "");
  EXPECT_EQ(metrics.missions_unfinished(), 1u);
  // A refused duplicate of mission 4's id: mission 4 goes on.
  EXPECT_EQ(metrics.AddStatus(4, MissionPhase::kRejected, 0, {}), "");
  EXPECT_EQ(metrics.missions_unfinished(), 1u);
  metrics.AddFrame(Frame(0, Carriers(0)), nullptr);
  metrics.Drain();
  EXPECT_TRUE(metrics.TakeMissionRows().empty());  // nothing finished
  EXPECT_EQ(metrics.missions_unfinished(), 1u);
  EXPECT_EQ(metrics.missions_done() + metrics.missions_aborted(), 0u);
}

TEST(RunMetricsTest, LateNewsOfAWrittenMissionIsIgnoredAndItsIdIsUsedAgainWithQueued) {
  RunMetrics metrics(Params());
  metrics.AddFrame(Frame(0, Carriers(0)), nullptr);
  // Statuses without an order: an "unknown" mission, written as soon as it ends.
  metrics.AddStatus(9, MissionPhase::kQueued, 1, {7.0, 7.0});
  metrics.AddStatus(9, MissionPhase::kDone, 3, {3.0, 3.0});
  EXPECT_EQ(metrics.TakeMissionRows(),
            std::vector<std::string>{"9,unknown,,,DONE,1,,,,,3,,,,,,,,,"});
  // An end with nothing before it leaves nothing.
  metrics.AddStatus(10, MissionPhase::kDone, 3, {3.0, 3.0});
  // Late news of mission 9.
  metrics.AddStatus(9, MissionPhase::kGathering, 4, {7.0, 7.0});
  metrics.AddStatus(9, MissionPhase::kDone, 5, {7.0, 7.0});
  EXPECT_TRUE(metrics.TakeMissionRows().empty());
  EXPECT_EQ(metrics.missions_unfinished(), 0u);
  // QUEUED: the id names a new mission.
  metrics.AddStatus(9, MissionPhase::kQueued, 10, {7.0, 7.0});
  EXPECT_EQ(metrics.missions_unfinished(), 1u);
  metrics.AddStatus(9, MissionPhase::kAborted, 12, {6.0, 6.0});
  EXPECT_EQ(metrics.TakeMissionRows(),
            std::vector<std::string>{"9,unknown,,,ABORTED,10,,,,,,,,,,,,,,"});
  // An order reuses a written id too.
  metrics.AddOrder(fixtures::Thesis(9), 0);
  EXPECT_EQ(metrics.missions_unfinished(), 1u);
  EXPECT_EQ(metrics.missions_done(), 1u);
  EXPECT_EQ(metrics.missions_aborted(), 1u);
}

TEST(RunMetricsTest, AFrameLeavingTheHistoryFeedsAMissionWhoseEndIsNotKnown) {
  LogLines log;
  RunMetrics metrics(Params(), log.Log());
  metrics.AddOrder(fixtures::Thesis(7), 0);
  metrics.AddOrder(fixtures::Thesis(8), 0);
  metrics.AddStatus(7, MissionPhase::kTransport, 10, {7.0, 7.0});  // 8's comes late
  // 16000 robots: the history holds 256 frames; 300 frames evict ticks 0..43.
  Robots robots = Carriers(0);
  for (std::uint16_t id = 3; id < 16000; ++id) {
    robots.push_back(
        {id, {static_cast<double>(id % 100) * 2.0, static_cast<double>(id / 100) * 2.0}});
  }
  for (std::uint64_t tick = 0; tick < 300; ++tick) {
    const Robots carriers = Carriers(tick);
    std::copy(carriers.begin(), carriers.end(), robots.begin());
    ASSERT_TRUE(metrics.AddFrame(Frame(tick, robots), nullptr));
  }
  EXPECT_TRUE(log.lines.empty());
  for (std::uint16_t id : {7, 8}) {
    metrics.AddStatus(id, MissionPhase::kTransport, 10, {7.0, 7.0});
    metrics.AddStatus(id, MissionPhase::kUnloading, 50, {3.0, 3.0});
    metrics.AddStatus(id, MissionPhase::kDone, 51, {3.0, 3.0});
  }
  const std::vector<std::string> rows = metrics.TakeMissionRows();
  ASSERT_EQ(rows.size(), 2u);
  // Mission 7 took ticks 10..43 as they left and 44..50 from the history: 40 ticks.
  EXPECT_EQ(Field(rows[0], 0), "7");
  EXPECT_EQ(Field(rows[0], 11), "40");
  EXPECT_EQ(Field(rows[0], 13), "5");  // 40 x 0.125 m
  // Mission 8's window began before the oldest kept frame: from tick 44 on.
  EXPECT_EQ(Field(rows[1], 0), "8");
  EXPECT_EQ(Field(rows[1], 11), "6");
  EXPECT_TRUE(
      log.Has("W mission 8 began at tick 10, before the oldest kept frame (tick 44); its metrics "
              "start there"));
}

// A long-lived recorder in real time: frames leave the history by wall time as well (statuses
// come seconds late, not 33 minutes), so its memory stops growing.
TEST(RunMetricsTest, FramesOlderThanTheWallWindowLeaveTheHistory) {
  for (const double window_s : {0.0, 10.05}) {
    LogLines log;
    RunMetricsParams params = Params();
    params.history_wall_s = window_s;
    RunMetrics metrics(params, log.Log());
    metrics.AddOrder(fixtures::Thesis(8), 0);
    // 300 frames at 10 Hz (of 3 robots: the tick count alone keeps 20,000 frames).
    for (std::uint64_t tick = 0; tick < 300; ++tick) {
      MetricsFrame frame = Frame(tick, Carriers(tick));
      frame.wall_s = 1000.0 + 0.1 * static_cast<double>(tick);
      ASSERT_TRUE(metrics.AddFrame(std::move(frame), nullptr));
    }
    metrics.AddStatus(8, MissionPhase::kTransport, 10, {7.0, 7.0});  // late
    metrics.AddStatus(8, MissionPhase::kUnloading, 250, {3.0, 3.0});
    metrics.AddStatus(8, MissionPhase::kDone, 251, {3.0, 3.0});
    const std::vector<std::string> rows = metrics.TakeMissionRows();
    ASSERT_EQ(rows.size(), 1u) << window_s;
    if (window_s == 0.0) {
      EXPECT_EQ(Field(rows[0], 11), "240");  // ticks 10..250: every frame kept
      for (const std::string& line : log.lines) EXPECT_NE(line.rfind("W ", 0), 0u) << line;
    } else {
      // Kept: the frames within 10.05 s of the newest (tick 299 at 1029.9 s): 199..299.
      EXPECT_EQ(Field(rows[0], 11), "51");
      EXPECT_TRUE(log.Has(
          "W mission 8 began at tick 10, before the oldest kept frame (tick 199); its metrics "
          "start there"));
    }
  }
}

TEST(RunMetricsTest, DrainWritesFinishedMissionsStillWaitingForFrames) {
  RunMetrics metrics(Params());
  metrics.AddOrder(fixtures::Thesis(7), 0);
  for (std::uint64_t tick = 0; tick <= 3; ++tick)
    metrics.AddFrame(Frame(tick, Carriers(tick)), nullptr);
  metrics.AddStatus(7, MissionPhase::kTransport, 1, {7.0, 7.0});
  metrics.AddStatus(7, MissionPhase::kUnloading, 9, {3.0, 3.0});
  metrics.AddStatus(7, MissionPhase::kDone, 10, {3.0, 3.0});
  EXPECT_TRUE(metrics.TakeMissionRows().empty());  // frames up to tick 9 are not in
  metrics.Drain();
  const std::vector<std::string> rows = metrics.TakeMissionRows();
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_EQ(Field(rows[0], 11), "2");  // ticks 1..3
  EXPECT_EQ(metrics.missions_done(), 1u);
}

TEST(RunMetricsTest, RunRowSummarisesSamplesMissionsAndTheLastFrame) {
  RunMetrics metrics(Params(1.0));
  EXPECT_EQ(metrics.RunRow("r", 5), "r,5,0,0,0,0,,0,0,0,,,");
  // 2 swarms at 0 s, 1 swarm at 1 s, 3 swarms at 1.5 s (not sampled).
  metrics.AddFrame(Frame(0, {{0, {1.0, 1.0}}, {1, {1.5, 1.0}}, {2, {5.0, 5.0}}}), nullptr);
  metrics.AddFrame(Frame(10, {{0, {1.0, 1.0}}, {1, {1.5, 1.0}}, {2, {2.0, 1.0}}}), nullptr);
  metrics.AddFrame(Frame(15, {{0, {1.0, 1.0}}, {1, {3.0, 1.0}}, {2, {5.0, 1.0}}}), nullptr);
  metrics.AddStatus(4, MissionPhase::kQueued, 15, {1.0, 1.0});
  metrics.AddStatus(4, MissionPhase::kAborted, 15, {1.0, 1.0});
  const std::string row = metrics.RunRow("run_3", -3);
  EXPECT_EQ(row.rfind("run_3,-3,3,15,1.5,2,1.5,3,0,1,", 0), 0u) << row;
  // The last frame's dispersion: three robots 2 m apart cover three 1 m discs of the arena.
  EXPECT_NEAR(std::stod(Field(row, 10)), 3.0 * M_PI / (111.0 * 111.0 * 0.01), 0.002);
  EXPECT_EQ(Field(row, 11), "2");
  EXPECT_EQ(Field(row, 12), "0");
}

TEST(RunMetricsTest, MissionsBeyondTheLimitAreNotFollowed) {
  RunMetrics metrics(Params());
  for (std::size_t id = 0; id < RunMetrics::kMaxMissions; ++id) {
    ASSERT_EQ(metrics.AddStatus(static_cast<std::uint16_t>(id), MissionPhase::kQueued, 0, {}), "");
  }
  EXPECT_EQ(metrics.AddStatus(5000, MissionPhase::kQueued, 0, {}),
            "not following mission 5000: 4096 missions followed already");
  EXPECT_EQ(metrics.AddOrder(fixtures::Thesis(5001), 0),
            "not following mission 5001: 4096 missions followed already");
  // A mission followed already still takes its order.
  EXPECT_EQ(metrics.AddOrder(fixtures::Thesis(7), 0), "");
  EXPECT_EQ(metrics.missions_unfinished(), RunMetrics::kMaxMissions);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
