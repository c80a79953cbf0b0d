// The dispatcher's policy on made-up swarms: its verdicts, count-only picking, the missions
// file's schedule, recruiting with a statist, LOADED / UNLOADED and the silent-leader watchdog.
#include "swarm_transport/core/dispatcher_policy.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "fixtures.h"

namespace swarm_transport {
namespace core {
namespace {

using fixtures::Report;
using fixtures::Thesis;

// Records what the policy does.
struct Outlet : DispatcherOutlet {
  std::vector<std::pair<MissionSpec, std::uint64_t>> orders;
  std::vector<std::pair<std::uint16_t, std::string>> rejected;
  std::vector<std::pair<std::uint16_t, std::string>> aborted;
  std::vector<Signal> events;
  std::vector<std::uint16_t> statists_up;
  std::vector<std::uint16_t> statists_down;
  std::vector<DispatcherAnswer> answers;
  std::vector<std::string> warnings;

  void Order(const MissionSpec& spec, std::uint64_t start_tick) override {
    orders.emplace_back(spec, start_tick);
  }
  void Rejected(const MissionSpec& spec, const std::string& reason) override {
    rejected.emplace_back(spec.id, reason);
  }
  void Aborted(const MissionSpec& spec, const std::string& reason) override {
    aborted.emplace_back(spec.id, reason);
  }
  void Event(const Signal& signal, const char*) override { events.push_back(signal); }
  void StatistUp(std::uint16_t id, Vec2, int) override { statists_up.push_back(id); }
  void StatistDown(std::uint16_t id, int) override { statists_down.push_back(id); }
  void Answer(const DispatcherAnswer& answer) override { answers.push_back(answer); }
  void Log(bool warn, const std::string& text) override {
    if (warn) warnings.push_back(text);
  }
};

// Robots 0 .. n-1 in a row along y = 1, 0.5 m apart (outside the Thesis and recruit objects).
std::map<std::uint16_t, PlannerRobot> Row(int n) {
  std::map<std::uint16_t, PlannerRobot> robots;
  for (int i = 0; i < n; ++i) robots[i] = {{1.0 + 0.5 * i, 1.0}, Angle(0.0)};
  return robots;
}

// A recruiting order for one robot: Thesis's mission, a 2 x 2 object at (5, 5) to (2, 5).
MissionSpec OneRecruit(std::uint16_t id) {
  MissionSpec recruit = Thesis(id);
  recruit.range_from = recruit.range_to = 0;
  recruit.recruit = true;
  recruit.robot_count = 1;
  recruit.object_centre = {5.0, 5.0};
  recruit.target = {2.0, 5.0};
  return recruit;
}

struct PolicyTest : ::testing::Test {
  double now_s = 0.0;
  Outlet outlet;

  DispatcherPolicyParams Params(bool lockstep) {
    DispatcherPolicyParams p;
    p.book.tick_period_s = 0.1;
    p.book.loaded_delay_s = 0.25;
    p.book.unloaded_delay_s = -1.0;
    p.book.max_live_missions = 4;
    p.book.silent_after_s = 5.0;
    p.lockstep = lockstep;
    p.start_delay_s = 1.0;
    p.clock = [this] { return now_s; };
    return p;
  }
};

TEST_F(PolicyTest, VerdictsRefuseBadInputAndChangeNothing) {
  DispatcherPolicy policy(Params(false), &outlet);
  policy.SetSwarm(0, Row(5));
  const auto ok = policy.Submit(Thesis(7), "service", true, true);
  ASSERT_TRUE(ok.accepted) << ok.message;
  ASSERT_EQ(outlet.orders.size(), 1u);
  EXPECT_EQ(outlet.orders[0].first.id, 7);
  // The same id again, a robot the swarm does not have, an inverted range, a NaN target.
  MissionSpec unknown = Thesis(8);
  unknown.range_to = 9;
  MissionSpec inverted = Thesis(9);
  inverted.range_from = 3;
  inverted.range_to = 1;
  MissionSpec nan = Thesis(10);
  nan.target.x = std::nan("");
  nan.all_finite = false;
  for (const MissionSpec& bad : {Thesis(7), unknown, inverted, nan}) {
    const auto verdict = policy.Submit(bad, "service", true, true);
    EXPECT_FALSE(verdict.accepted) << bad.id;
    EXPECT_FALSE(verdict.reason.empty());
  }
  EXPECT_EQ(outlet.orders.size(), 1u);
  EXPECT_EQ(outlet.rejected.size(), 4u);
  EXPECT_EQ(policy.book().LiveCount(), 1);
  EXPECT_EQ(outlet.warnings.size(), 4u);
}

TEST_F(PolicyTest, ACountOnlyOrderIsSentWithTheIdleRobotsItPicked) {
  DispatcherPolicy policy(Params(false), &outlet);
  MissionSpec count = Thesis(3);
  count.range_from = count.range_to = 0;
  count.robot_count = 2;
  // No swarm heard yet: nothing to pick from, and the reason says so.
  const auto early = policy.Submit(count, "service", false, true);
  EXPECT_FALSE(early.accepted);
  EXPECT_NE(early.reason.find("no robot positions heard yet"), std::string::npos) << early.reason;
  EXPECT_TRUE(outlet.orders.empty());
  policy.SetSwarm(4, Row(6));
  ASSERT_TRUE(policy.Submit(Thesis(1), "service", false, true).accepted);  // robots 0 .. 2
  const auto verdict = policy.Submit(count, "service", false, true);
  ASSERT_TRUE(verdict.accepted) << verdict.message;
  ASSERT_EQ(outlet.orders.size(), 2u);
  const MissionSpec& order = outlet.orders[1].first;
  EXPECT_EQ(order.robot_count, 0);
  ASSERT_EQ(order.robot_ids.size(), 2u);
  for (std::uint16_t id : order.robot_ids) EXPECT_GE(id, 3) << "a busy robot was picked";
  // More than the idle robots left: refused.
  count.id = 4;
  count.robot_count = 2;
  EXPECT_FALSE(policy.Submit(count, "service", false, true).accepted);
}

TEST_F(PolicyTest, NoRobotWhoseProcessIsNotConnectedIsPickedOrRecruited) {
  // Robot 1's process was killed (its body still stands in the world and is heard): a robot
  // picked then would never get its order, and its mission's GATHERING would wait for it.
  DispatcherPolicy policy(Params(false), &outlet);
  policy.SetSwarm(0, Row(3));
  policy.SetUnreachable({1});
  MissionSpec count = Thesis(3);
  count.range_from = count.range_to = 0;
  count.robot_count = 3;
  const auto all = policy.Submit(count, "service", false, true);
  EXPECT_FALSE(all.accepted);
  EXPECT_NE(all.reason.find("robot(s) 1, whose process is not connected"), std::string::npos)
      << all.reason;
  count.robot_count = 2;
  const auto two = policy.Submit(count, "service", false, true);
  ASSERT_TRUE(two.accepted) << two.message;
  ASSERT_EQ(outlet.orders.size(), 1u);
  EXPECT_EQ(outlet.orders[0].first.robot_ids, (std::vector<std::uint16_t>{0, 2}));
  // Connected again: it may be picked (robots 0 and 2 are busy now).
  policy.SetUnreachable({});
  MissionSpec one = count;
  one.id = 4;
  one.robot_count = 1;
  ASSERT_TRUE(policy.Submit(one, "service", false, true).accepted);
  EXPECT_EQ(outlet.orders[1].first.robot_ids, (std::vector<std::uint16_t>{1}));
  // A recruit does not take it either while it is unreachable.
  DispatcherPolicy recruiting(Params(false), &outlet);
  auto robots = Row(2);
  robots[1].position = {5.0, 5.0};  // inside the recruit's object from the start
  recruiting.OnSwarm(0, robots);
  recruiting.SetUnreachable({1});
  const MissionSpec recruit = OneRecruit(5);
  ASSERT_TRUE(recruiting.Submit(recruit, "service", false, true).accepted);
  recruiting.OnSwarm(9, robots);
  EXPECT_EQ(outlet.orders.size(), 2u) << "robot 1 was recruited while unreachable";
}

TEST_F(PolicyTest, LockstepFileMissionsAreStampedAndAnsweredAtTheFirstSwarm) {
  DispatcherPolicy policy(Params(true), &outlet);
  MissionSpec late = Thesis(0);
  late.range_from = 3;
  late.range_to = 6;
  policy.SetFileMissions({Thesis(0), late}, {0, 30});
  EXPECT_TRUE(policy.OnSwarm(2, Row(8)).empty());
  // start_delay_s 1 s = tick 10; the second at its own tick.
  ASSERT_EQ(outlet.orders.size(), 2u);
  EXPECT_EQ(outlet.orders[0].second, 10u);
  EXPECT_EQ(outlet.orders[1].second, 30u);
  ASSERT_EQ(outlet.answers.size(), 1u);
  const DispatcherAnswer& answer = outlet.answers[0];
  EXPECT_TRUE(answer.has_positions);
  EXPECT_EQ(answer.checked_tick, 2u);
  EXPECT_EQ(answer.orders, (std::vector<std::pair<std::uint16_t, std::uint64_t>>{
                               {outlet.orders[0].first.id, 10}, {outlet.orders[1].first.id, 30}}));
  EXPECT_EQ(answer.hold_from_tick, 0u);  // no recruit: no later tick waits for its answers
  // Later swarms schedule nothing more; each is answered, naming nothing.
  policy.OnSwarm(3, Row(8));
  EXPECT_EQ(outlet.orders.size(), 2u);
  ASSERT_EQ(outlet.answers.size(), 2u);
  EXPECT_EQ(outlet.answers[1].checked_tick, 3u);
  EXPECT_TRUE(outlet.answers[1].orders.empty());
  EXPECT_FALSE(outlet.answers[1].status.has_value());
}

TEST_F(PolicyTest, RealTimeFileMissionsAreLeftToTheCallersTimers) {
  DispatcherPolicy policy(Params(false), &outlet);
  policy.SetFileMissions({Thesis(1), Thesis(2)}, {0, 20});
  const auto later = policy.OnSwarm(0, Row(5));
  EXPECT_EQ(later, (std::vector<std::pair<std::uint64_t, double>>{{0, 1.0}, {20, 2.0}}));
  EXPECT_TRUE(outlet.orders.empty());
  policy.SubmitFileMissions(20);
  ASSERT_EQ(outlet.orders.size(), 1u);
  EXPECT_EQ(outlet.orders[0].first.id, 2);
  EXPECT_TRUE(policy.OnSwarm(1, Row(5)).empty());  // only once
}

TEST_F(PolicyTest, ARecruitSendsItsOrderTheTickAfterEnoughRobotsEntered) {
  DispatcherPolicy policy(Params(true), &outlet);
  policy.OnSwarm(0, Row(4));
  MissionSpec recruit = OneRecruit(0);
  recruit.robot_count = 2;
  const auto verdict = policy.Submit(recruit, "service", true, true);
  ASSERT_TRUE(verdict.accepted) << verdict.message;
  ASSERT_EQ(outlet.answers.size(), 2u);
  ASSERT_EQ(outlet.answers[1].recruiting.size(), 1u);
  const RecruitStatist& statist = outlet.answers[1].recruiting[0];
  EXPECT_EQ(statist.statist_id, kRecruitStatistId);
  EXPECT_EQ(statist.from_tick, 1u);
  EXPECT_EQ(statist.copies, DispatcherPolicy::kRecruitStatistCopies);
  // Every tick after its statist's first waits for the answer to the tick before.
  EXPECT_EQ(outlet.answers[1].hold_from_tick, 2u);
  EXPECT_TRUE(outlet.orders.empty());
  // Robot 2 enters at tick 5, robot 0 at tick 6: the order goes out for tick 7.
  auto robots = Row(4);
  robots[2].position = {5.0, 5.0};
  policy.OnSwarm(5, robots);
  EXPECT_TRUE(outlet.orders.empty());
  EXPECT_EQ(outlet.answers.back().checked_tick, 5u);
  robots[0].position = {5.2, 4.8};
  policy.OnSwarm(6, robots);
  ASSERT_EQ(outlet.orders.size(), 1u);
  EXPECT_EQ(outlet.orders[0].first.robot_ids, (std::vector<std::uint16_t>{0, 2}));
  EXPECT_EQ(outlet.orders[0].second, 7u);
  EXPECT_TRUE(outlet.answers.back().recruiting.empty());
  EXPECT_EQ(outlet.answers.back().hold_from_tick, 0u);
  EXPECT_EQ(outlet.answers.back().orders,
            (std::vector<std::pair<std::uint16_t, std::uint64_t>>{{verdict.id, 7}}));
  EXPECT_TRUE(outlet.statists_up.empty());  // lock-step: the simulator places it
}

TEST_F(PolicyTest, RealTimeRecruitPlacesAndRemovesItsStatist) {
  DispatcherPolicy policy(Params(false), &outlet);
  policy.OnSwarm(0, Row(4));
  const MissionSpec recruit = OneRecruit(5);
  ASSERT_TRUE(policy.Submit(recruit, "service", false, true).accepted);
  EXPECT_EQ(outlet.statists_up, (std::vector<std::uint16_t>{kRecruitStatistId}));
  auto robots = Row(4);
  robots[3].position = {5.0, 5.0};
  policy.OnSwarm(9, robots);
  EXPECT_EQ(outlet.statists_down, (std::vector<std::uint16_t>{kRecruitStatistId}));
  ASSERT_EQ(outlet.orders.size(), 1u);
  EXPECT_EQ(outlet.orders[0].second, 0u);
  EXPECT_TRUE(outlet.answers.empty());
}

TEST_F(PolicyTest, LoadedIsSentWithItsDelayAndSignalsAreChecked) {
  DispatcherPolicy policy(Params(true), &outlet);
  policy.SetSwarm(0, Row(5));
  ASSERT_TRUE(policy.Submit(Thesis(7), "service", false, true).accepted);
  policy.OnStatus(Report(7, MissionPhase::kLoading, 40), "robot_0");
  ASSERT_EQ(outlet.events.size(), 1u);
  EXPECT_EQ(outlet.events[0].kind, MissionEventKind::kLoaded);
  EXPECT_EQ(outlet.events[0].not_before_tick, 43u);  // 40 + ceil(0.25 / 0.1)
  // Lock-step: an answer names the status it took and the LOADED it sent for it.
  ASSERT_EQ(outlet.answers.size(), 1u);
  ASSERT_TRUE(outlet.answers[0].status.has_value());
  EXPECT_TRUE(*outlet.answers[0].status == (StatusKey{7, MissionPhase::kLoading, 40}));
  ASSERT_EQ(outlet.answers[0].events.size(), 1u);
  EXPECT_EQ(outlet.answers[0].events[0].kind, MissionEventKind::kLoaded);
  // A status not booked is answered all the same, naming nothing.
  policy.SkipStatus(StatusKey{99, MissionPhase::kGathering, 41});
  ASSERT_EQ(outlet.answers.size(), 2u);
  EXPECT_TRUE(outlet.answers[1].events.empty());
  EXPECT_EQ(outlet.answers[1].status->mission_id, 99);
  EXPECT_FALSE(policy.Signal(99, MissionEventKind::kUnloaded).empty());
  EXPECT_FALSE(policy.Signal(7, static_cast<MissionEventKind>(5)).empty());
  EXPECT_EQ(outlet.events.size(), 1u);
  EXPECT_EQ(policy.Signal(7, MissionEventKind::kUnloaded), "");
  EXPECT_EQ(outlet.events.size(), 2u);
}

TEST_F(PolicyTest, ASilentMissionIsAbortedOnlyAfterTheWallGrace) {
  DispatcherPolicy policy(Params(true), &outlet);
  policy.SetSwarm(0, Row(5));
  ASSERT_TRUE(policy.Submit(Thesis(7), "service", false, true).accepted);
  policy.OnStatus(Report(7, MissionPhase::kGathering, 1), "robot_0");
  now_s = 10.0;  // silent for 10 s of the run's clock
  policy.Watchdog(100.0, 1.0);
  EXPECT_TRUE(outlet.aborted.empty());
  policy.Watchdog(100.5, 1.0);
  EXPECT_TRUE(outlet.aborted.empty());
  policy.Watchdog(101.0, 1.0);
  ASSERT_EQ(outlet.aborted.size(), 1u);
  EXPECT_EQ(outlet.aborted[0].first, 7);
  EXPECT_EQ(policy.book().LiveCount(), 0);
}

// Real time: an event is not latched, and a robot not yet connected to a restarted dispatcher
// missed the UNLOADED it owed (a soak slice: the mission stood in UNLOADING for good, issue 29).
TEST_F(PolicyTest, ASignalGoesAgainWhileItsMissionStaysInItsPhase) {
  DispatcherPolicyParams params = Params(false);
  params.book.silent_after_s = -1.0;
  params.signal_resend_s = 5.0;
  DispatcherPolicy policy(params, &outlet);
  policy.SetSwarm(0, Row(5));
  ASSERT_TRUE(policy.Submit(Thesis(7), "service", false, true).accepted);
  now_s = 1.0;
  policy.OnStatus(Report(7, MissionPhase::kLoading, 40), "robot_0");
  ASSERT_EQ(outlet.events.size(), 1u);
  now_s = 5.9;  // not yet
  policy.Watchdog(0.0, 1.0);
  EXPECT_EQ(outlet.events.size(), 1u);
  now_s = 6.0;  // still LOADING 5 s later: the same LOADED again, then 5 s after that
  policy.Watchdog(0.0, 1.0);
  ASSERT_EQ(outlet.events.size(), 2u);
  EXPECT_EQ(outlet.events[1].kind, MissionEventKind::kLoaded);
  EXPECT_EQ(outlet.events[1].not_before_tick, outlet.events[0].not_before_tick);
  now_s = 8.0;
  policy.Watchdog(0.0, 1.0);
  EXPECT_EQ(outlet.events.size(), 2u);
  now_s = 11.0;
  policy.Watchdog(0.0, 1.0);
  EXPECT_EQ(outlet.events.size(), 3u);
  // In TRANSPORT nothing is owed.
  policy.OnStatus(Report(7, MissionPhase::kTransport, 200), "robot_0");
  now_s = 30.0;
  policy.Watchdog(0.0, 1.0);
  EXPECT_EQ(outlet.events.size(), 3u);
  // Lock-step delivers every signal in its round: never again.
  DispatcherPolicy lockstep(Params(true), &outlet);
  lockstep.SetSwarm(0, Row(5));
  ASSERT_TRUE(lockstep.Submit(Thesis(8), "service", false, true).accepted);
  now_s = 31.0;
  lockstep.OnStatus(Report(8, MissionPhase::kLoading, 40), "robot_0");
  ASSERT_EQ(outlet.events.size(), 4u);
  now_s = 100.0;
  lockstep.Watchdog(0.0, 1.0);
  EXPECT_EQ(outlet.events.size(), 4u);
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
