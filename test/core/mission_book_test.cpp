// The dispatcher's bookkeeping: verdicts, ids, phases from first leaders' reports, the
// LOADED / UNLOADED signals and the status table.
#include "swarm_transport/core/mission_book.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

#include "fixtures.h"

namespace swarm_transport {
namespace core {
namespace {

using fixtures::Report;
using fixtures::Robots;
using fixtures::Thesis;

MissionBookParams Params() {
  MissionBookParams p;
  p.tick_period_s = 1.1;
  p.loaded_delay_s = 2.0;
  p.unloaded_delay_s = -1.0;  // only on a signal
  p.max_live_missions = 2;
  return p;
}

TEST(MissionBookTest, AcceptsRejectsAndChoosesIds) {
  MissionBook book(Params());
  const auto a = book.Submit(Thesis(0), "service", true, false, Robots(25), 1.0);
  ASSERT_TRUE(a.accepted) << a.message;
  EXPECT_EQ(a.id, 1);  // the first free id
  EXPECT_EQ(a.spec.id, 1);
  EXPECT_NE(a.message.find("mission 1 queued: 3 robots [0, 3), 1 leader(s)"), std::string::npos)
      << a.message;
  // A robot the swarm does not have: refused, and the automatic id is not used up.
  const auto bad = book.Submit(Thesis(0), "service", true, false, Robots(2), 1.0);
  EXPECT_FALSE(bad.accepted);
  EXPECT_EQ(bad.message.substr(0, 19), "mission 2 rejected:") << bad.message;
  EXPECT_FALSE(bad.reason.empty());
  const auto b = book.Submit(Thesis(0), "service", true, false, Robots(25), 1.0);
  ASSERT_TRUE(b.accepted) << b.message;
  EXPECT_EQ(b.id, 2);
  // A live id again: a duplicate; beyond the live limit: refused with the count.
  EXPECT_FALSE(book.Submit(Thesis(1), "topic", false, false, Robots(25), 1.0).accepted);
  const auto third = book.Submit(Thesis(9), "service", true, false, Robots(25), 1.0);
  EXPECT_FALSE(third.accepted);
  EXPECT_NE(third.reason.find("too many live missions (2"), std::string::npos) << third.reason;
  EXPECT_EQ(book.LiveCount(), 2);
}

TEST(MissionBookTest, PhasesSignalsAndTheEndOfAMission) {
  MissionBook book(Params());
  ASSERT_TRUE(book.Submit(Thesis(7), "service", false, false, Robots(25), 0.0).accepted);
  // QUEUED again: no phase change.
  auto out = book.OnStatus(Report(7, MissionPhase::kQueued, 0), 0.0);
  EXPECT_FALSE(out.entered);
  out = book.OnStatus(Report(7, MissionPhase::kGathering, 1), 0.1);
  EXPECT_TRUE(out.entered);
  EXPECT_TRUE(out.signals.empty());
  // LOADING at tick 65: LOADED due at 65 + ceil(2.0 / 1.1) = 67, once.
  out = book.OnStatus(Report(7, MissionPhase::kLoading, 65), 71.5);
  ASSERT_EQ(out.signals.size(), 1u);
  EXPECT_EQ(out.signals[0].kind, MissionEventKind::kLoaded);
  EXPECT_EQ(out.signals[0].not_before_tick, 67u);
  EXPECT_TRUE(book.OnStatus(Report(7, MissionPhase::kLoading, 66), 72.6).signals.empty());
  // UNLOADED only on a signal (negative delay).
  EXPECT_TRUE(book.OnStatus(Report(7, MissionPhase::kUnloading, 135), 148.5).signals.empty());
  EXPECT_EQ(book.Signal(7, MissionEventKind::kUnloaded, 0.0), "");
  EXPECT_EQ(book.Signal(8, MissionEventKind::kUnloaded, 0.0), "mission 8 is unknown");
  out = book.OnStatus(Report(7, MissionPhase::kDone, 137), 150.7);
  EXPECT_TRUE(out.entered);
  EXPECT_FALSE(book.Find(7)->Live());
  EXPECT_EQ(book.Signal(7, MissionEventKind::kLoaded, 0.0), "mission 7 is finished (DONE)");
  // Late news of it changes nothing; its id may be used again.
  EXPECT_FALSE(book.OnStatus(Report(7, MissionPhase::kTransport, 136), 151.0).ignored.empty());
  EXPECT_EQ(book.Find(7)->phase, MissionPhase::kDone);
  const auto again = book.Submit(Thesis(7), "service", false, false, Robots(25), 200.0);
  ASSERT_TRUE(again.accepted) << again.message;
  EXPECT_EQ(book.Find(7)->phase, MissionPhase::kQueued);
  // The table: seconds per phase, from each entry to the next.
  EXPECT_NE(book.Table(210.0).find("1 mission(s) tracked, 1 live"), std::string::npos);
  EXPECT_NE(book.Table(210.0).find(" Q 10.0"), std::string::npos) << book.Table(210.0);
}

TEST(MissionBookTest, FollowsAMissionSeenFirstInAStatusAndAttachesItsOrder) {
  MissionBook book(Params());
  auto out = book.OnStatus(Report(5, MissionPhase::kGathering, 3), 0.3);
  EXPECT_TRUE(out.followed);
  EXPECT_EQ(book.Find(5)->source, "status");
  EXPECT_FALSE(book.Find(5)->has_spec);
  // Its order heard later on the topic is attached, not refused as a duplicate ...
  const auto attached = book.Submit(Thesis(5), "topic", false, true, Robots(25), 0.4);
  EXPECT_TRUE(attached.accepted);
  EXPECT_TRUE(attached.attached);
  EXPECT_TRUE(book.Find(5)->has_spec);
  EXPECT_EQ(book.Find(5)->phase, MissionPhase::kGathering);
  // ... but a submission naming it is a duplicate.
  EXPECT_FALSE(book.Submit(Thesis(5), "service", false, false, Robots(25), 0.5).accepted);
  // A REJECTED from elsewhere about a running mission or an unknown one changes nothing.
  EXPECT_FALSE(book.OnStatus(Report(5, MissionPhase::kRejected, 0), 0.6).ignored.empty());
  EXPECT_FALSE(book.OnStatus(Report(6, MissionPhase::kRejected, 0), 0.6).ignored.empty());
  EXPECT_EQ(book.Find(6), nullptr);
  EXPECT_TRUE(book.Find(5)->Live());
}

TEST(MissionBookTest, ForgetsTheOldestFinishedMissionsFirst) {
  MissionBookParams p = Params();
  p.max_live_missions = 10;
  MissionBook book(p);
  for (std::size_t k = 0; k < MissionBook::kMaxFinishedMissions + 5; ++k) {
    const auto v = book.Submit(Thesis(0), "service", true, false, Robots(25), 0.0);
    ASSERT_TRUE(v.accepted) << v.message;
    book.OnStatus(Report(v.id, MissionPhase::kAborted, 1), 0.0);
  }
  EXPECT_EQ(book.entries().size(), MissionBook::kMaxFinishedMissions);
  EXPECT_EQ(book.Find(1), nullptr);
  EXPECT_NE(book.Find(6), nullptr);
}

TEST(MissionBookTest, AProgressReportWithAReasonShowsInTheTable) {
  MissionBook book(Params());
  ASSERT_TRUE(book.Submit(Thesis(7), "service", false, false, Robots(25), 0.0).accepted);
  book.OnStatus(Report(7, MissionPhase::kGathering, 10), 1.0);
  book.OnProgress(Report(7, MissionPhase::kGathering, 20), 2.0);  // no reason: none shown
  EXPECT_EQ(book.Find(7)->reason, "");
  EXPECT_NE(book.Table(3.0).find(" G 2.0\n"), std::string::npos) << book.Table(3.0);  // row ends
  MissionReport lost = Report(7, MissionPhase::kGathering, 30);
  lost.reason = "robot(s) 2 lost (not heard for 5 ticks): the mission goes on without them";
  book.OnProgress(lost, 3.0);
  EXPECT_NE(book.Table(4.0).find(" | " + lost.reason), std::string::npos) << book.Table(4.0);
  EXPECT_EQ(book.Find(7)->phase, MissionPhase::kGathering);  // progress changes no phase
}

TEST(MissionBookTest, ARunningMissionWhoseFirstLeaderFellSilentIsEnded) {
  MissionBookParams p = Params();
  p.silent_after_s = 30.0;
  MissionBook book(p);
  ASSERT_TRUE(book.Submit(Thesis(7), "service", false, false, Robots(25), 0.0).accepted);
  // QUEUED waits its turn however long: not silent.
  EXPECT_TRUE(book.Silent(100.0).empty());
  book.OnStatus(Report(7, MissionPhase::kGathering, 90), 100.0);
  book.OnProgress(Report(7, MissionPhase::kGathering, 140), 120.0);  // a heartbeat
  EXPECT_TRUE(book.Silent(150.0).empty());
  const auto silent = book.Silent(150.5);
  ASSERT_EQ(silent.size(), 1u);
  EXPECT_EQ(silent[0].first, 7);
  EXPECT_NE(silent[0].second.find("first leader (robot 0) silent for 30.5 s in GATHERING"),
            std::string::npos)
      << silent[0].second;
  EXPECT_TRUE(book.Abort(7, silent[0].second, 150.5));
  EXPECT_EQ(book.Find(7)->phase, MissionPhase::kAborted);
  EXPECT_EQ(book.Find(7)->reason, silent[0].second);
  EXPECT_FALSE(book.Abort(7, "again", 151.0));  // not live any more
  EXPECT_TRUE(book.Silent(500.0).empty());
  // Without a limit nothing is ever silent.
  MissionBook patient(Params());
  ASSERT_TRUE(patient.Submit(Thesis(7), "service", false, false, Robots(25), 0.0).accepted);
  patient.OnStatus(Report(7, MissionPhase::kTransport, 1), 0.0);
  EXPECT_TRUE(patient.Silent(1e6).empty());
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
