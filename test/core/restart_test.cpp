// Missions outlive their dispatcher, the record its recorder (issue 29): the dispatcher's book
// rebuilt from re-sent statuses, ids after a restart, and a restarted recorder's take-over of the
// earlier files (no row twice, recovered rows marked, counts carried).
#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "fixtures.h"
#include "swarm_transport/core/mission_book.h"
#include "swarm_transport/core/record_resume.h"
#include "swarm_transport/core/run_metrics.h"

namespace swarm_transport {
namespace core {
namespace {

using fixtures::Report;
using fixtures::Robots;
using fixtures::Thesis;

MissionBookParams Params() {
  MissionBookParams p;
  p.tick_period_s = 0.1;
  p.loaded_delay_s = 2.0;
  p.unloaded_delay_s = 2.0;
  return p;
}

MissionSpec Other(std::uint16_t id) {
  MissionSpec m = Thesis(id);
  m.range_from = 3;
  m.range_to = 6;
  return m;
}

TEST(RestartTest, ABookRebuildsItsTableFromReSentStatusesWithTheirOrders) {
  MissionBook book(Params());
  const MissionSpec gathering = Thesis(4);
  const MissionSpec transport = Other(9);
  MissionBook::StatusOutcome a =
      book.Restore(Report(4, MissionPhase::kGathering, 30), &gathering, 1.0);
  EXPECT_TRUE(a.followed);
  EXPECT_TRUE(a.signals.empty());
  MissionBook::StatusOutcome b =
      book.Restore(Report(9, MissionPhase::kTransport, 80), &transport, 1.0);
  EXPECT_TRUE(b.followed);
  ASSERT_NE(book.Find(4), nullptr);
  EXPECT_TRUE(book.Find(4)->has_spec);
  EXPECT_EQ(book.Find(4)->source, "resent");
  EXPECT_EQ(book.Find(4)->robots_assigned, 3);
  EXPECT_EQ(book.Find(9)->phase, MissionPhase::kTransport);
  EXPECT_EQ(book.LiveCount(), 2);
  const std::string table = book.Table(2.0);
  EXPECT_NE(table.find("2 mission(s) tracked, 2 live"), std::string::npos) << table;
  EXPECT_NE(table.find("GATHERING"), std::string::npos) << table;
  // The same status again (another request) changes nothing; an older phase neither.
  EXPECT_FALSE(book.Restore(Report(4, MissionPhase::kGathering, 30), &gathering, 1.5).entered);
  const MissionBook::StatusOutcome old =
      book.Restore(Report(9, MissionPhase::kGathering, 10), &transport, 1.5);
  EXPECT_FALSE(old.ignored.empty());
  EXPECT_EQ(book.Find(9)->phase, MissionPhase::kTransport);
  // The mission goes on through its statuses: UNLOADED is due once at UNLOADING.
  const MissionBook::StatusOutcome unloading =
      book.OnStatus(Report(9, MissionPhase::kUnloading, 120), 3.0);
  ASSERT_EQ(unloading.signals.size(), 1u);
  EXPECT_EQ(unloading.signals[0].kind, MissionEventKind::kUnloaded);
  EXPECT_EQ(unloading.signals[0].not_before_tick, 140u);
}

TEST(RestartTest, AReSentLoadingMakesItsLoadedDueAndAReSentEndIsBookedFinished) {
  MissionBook book(Params());
  const MissionSpec loading = Thesis(2);
  const MissionBook::StatusOutcome out =
      book.Restore(Report(2, MissionPhase::kLoading, 50), &loading, 1.0);
  ASSERT_EQ(out.signals.size(), 1u);
  EXPECT_EQ(out.signals[0].kind, MissionEventKind::kLoaded);
  EXPECT_EQ(out.signals[0].not_before_tick, 70u);
  const MissionSpec done = Other(3);
  book.Restore(Report(3, MissionPhase::kDone, 90), &done, 1.0);
  ASSERT_NE(book.Find(3), nullptr);
  EXPECT_FALSE(book.Find(3)->Live());
  EXPECT_EQ(book.LiveCount(), 1);
}

TEST(RestartTest, NewIdsDoNotCollideWithReSentOnesAndALiveIdIsRefused) {
  MissionBook book(Params());
  const MissionSpec live = Thesis(5);
  const MissionSpec done = Other(7);
  book.Restore(Report(5, MissionPhase::kTransport, 80), &live, 1.0);
  book.Restore(Report(7, MissionPhase::kDone, 90), &done, 1.0);
  // An automatic id goes above every id re-sent (1..4 may have been used before the restart).
  MissionSpec next = Other(0);
  next.range_from = 6;
  next.range_to = 9;
  const MissionBook::Verdict fresh = book.Submit(next, "service", true, false, Robots(25), 2.0);
  ASSERT_TRUE(fresh.accepted) << fresh.message;
  EXPECT_EQ(fresh.id, 8);
  // An order reusing the live id (sent while the dispatcher was down): refused, with why.
  const MissionBook::Verdict reused = book.Submit(Other(5), "topic", false, false, Robots(25), 2.0);
  EXPECT_FALSE(reused.accepted);
  EXPECT_NE(reused.message.find("mission 5 rejected"), std::string::npos) << reused.message;
  EXPECT_FALSE(reused.reason.empty());
}

TEST(RestartTest, AReSentStatusWithoutAnOrderGetsTheOrderOfALaterResend) {
  MissionBook book(Params());
  book.Restore(Report(6, MissionPhase::kGathering, 20), nullptr, 1.0);
  ASSERT_NE(book.Find(6), nullptr);
  EXPECT_FALSE(book.Find(6)->has_spec);
  const MissionSpec order = Thesis(6);
  book.Restore(Report(6, MissionPhase::kGathering, 20), &order, 1.2);
  EXPECT_TRUE(book.Find(6)->has_spec);
  // An order naming another id is not attached.
  book.Restore(Report(11, MissionPhase::kGathering, 20), &order, 1.2);
  EXPECT_FALSE(book.Find(11)->has_spec);
}

RunMetricsParams MetricsParams() {
  RunMetricsParams p;
  p.local_range_m = 1.0;
  p.goal_tolerance_m = 0.15;
  p.sample_period_s = 1000.0;
  return p;
}

MetricsFrame Frame(std::uint64_t tick) {
  MetricsFrame frame;
  frame.tick = tick;
  frame.sim_time_s = 0.1 * static_cast<double>(tick);
  for (std::uint16_t id = 0; id < 6; ++id) {
    frame.ids.push_back(id);
    frame.positions.push_back({1.0 + id, 1.0});
  }
  return frame;
}

TEST(RestartTest, ARecorderWritesAMissionEndedInTheGapOnceAndMarksItRecovered) {
  RunMetrics metrics(MetricsParams());
  metrics.MarkRowWritten(1);  // written by the earlier recorder
  metrics.AddFrame(Frame(200), nullptr);
  const MissionSpec one = Thesis(1);
  const MissionSpec two = Other(2);
  // Mission 1's row exists: its re-sent DONE (two requests) writes nothing.
  EXPECT_EQ(metrics.AddResent(&one, 1, MissionPhase::kDone, 150, {3.0, 3.0}), "");
  EXPECT_TRUE(metrics.TakeMissionRows().empty());
  // Mission 2 ended in the gap: a comment and its row, once.
  EXPECT_EQ(metrics.AddResent(&two, 2, MissionPhase::kDone, 180, {3.0, 3.0}), "");
  metrics.AddResent(&two, 2, MissionPhase::kDone, 180, {3.0, 3.0});
  const std::vector<std::string> rows = metrics.TakeMissionRows();
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[0].rfind("# recovered: mission 2 ", 0), 0u) << rows[0];
  EXPECT_EQ(rows[1].rfind("2,transport,3,1,DONE,,,,,,180,", 0), 0u) << rows[1];
  metrics.AddResent(&two, 2, MissionPhase::kDone, 180, {3.0, 3.0});
  EXPECT_TRUE(metrics.TakeMissionRows().empty());
  EXPECT_EQ(metrics.missions_done(), 1u);
}

TEST(RestartTest, ARunningMissionReSentIsFollowedToItsEndAndStatusesAfterAreNotDoubled) {
  RunMetrics metrics(MetricsParams());
  const MissionSpec three = Thesis(3);
  metrics.AddFrame(Frame(100), nullptr);
  metrics.AddResent(&three, 3, MissionPhase::kTransport, 90, {6.0, 6.0});
  metrics.AddStatus(3, MissionPhase::kUnloading, 120, {3.0, 3.0});
  metrics.AddResent(&three, 3, MissionPhase::kUnloading, 120, {3.0, 3.0});
  metrics.AddStatus(3, MissionPhase::kDone, 130, {3.0, 3.0});
  metrics.AddFrame(Frame(131), nullptr);
  const std::vector<std::string> rows = metrics.TakeMissionRows();
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(rows[1].rfind("3,transport,3,1,DONE,,,,90,120,130,", 0), 0u) << rows[1];
  // The DONE re-sent later (a recorder's next request) is not written again.
  metrics.AddResent(&three, 3, MissionPhase::kDone, 130, {3.0, 3.0});
  EXPECT_TRUE(metrics.TakeMissionRows().empty());
}

TEST(RestartTest, EarlierFilesGiveTheirRowsCountsAndLastTick) {
  const std::string missions = std::string(RunMetrics::kMissionsHeader) +
                               "\n1,transport,3,1,DONE,0,1,2,3,4,5,,,,,,,,,\n"
                               "# a comment\n"
                               "2,leader,1,1,ABORTED,0,,,,,,,,,,,,,,\n"
                               "3,transport,3,1,DO";  // cut by the kill
  const std::string run = std::string(RunMetrics::kRunHeader) + "\nrun,1,8,400,40,4,2.5,2,1,1,,,\n";
  const std::string swarm = std::string(RunMetrics::kSwarmHeader) + "\n0,0,8,3,4\n390,39,8,2,5\n";
  EarlierRecord record;
  std::string error;
  ASSERT_TRUE(ReadEarlierRecord(missions, run, swarm, &record, &error)) << error;
  EXPECT_EQ(record.rows, (std::set<std::uint16_t>{1, 2}));
  EXPECT_EQ(record.done, 1u);
  EXPECT_EQ(record.aborted, 1u);
  EXPECT_EQ(record.samples, 4u);
  EXPECT_DOUBLE_EQ(record.swarm_count_sum, 10.0);
  ASSERT_TRUE(record.last_tick.has_value());
  EXPECT_EQ(*record.last_tick, 400u);
  EXPECT_EQ(CompleteLength(missions), missions.rfind('\n') + 1);
  // No files: nothing before. Files of something else: refused, with why.
  ASSERT_TRUE(ReadEarlierRecord("", "", "", &record, &error));
  EXPECT_TRUE(record.rows.empty());
  EXPECT_FALSE(record.last_tick.has_value());
  EXPECT_FALSE(ReadEarlierRecord("a,b\n1,2\n", "", "", &record, &error));
  EXPECT_NE(error.find("missions.csv"), std::string::npos) << error;
  EXPECT_EQ(GapComment(400, "T").rfind("# gap: the recorder restarted at T; nothing recorded after "
                                       "tick 400",
                                       0),
            0u);
}

TEST(RestartTest, CarriedCountsEnterTheRunRow) {
  RunMetrics metrics(MetricsParams());
  metrics.Carry(4, 10.0, 2, 1);
  EXPECT_EQ(metrics.missions_done(), 2u);
  EXPECT_EQ(metrics.missions_aborted(), 1u);
  EXPECT_EQ(metrics.samples(), 4u);
  const std::string row = metrics.RunRow("r", 1);
  EXPECT_EQ(row.rfind("r,1,0,0,0,4,2.5,0,2,1,", 0), 0u) << row;
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
