// The simulator's timed events (~events_file, issue 14): every kind read, a bad entry named,
// and the schedule hands out each event once, at its tick, in file order within a tick.
#include "swarm_transport/ros/common/event_schedule.h"

#include <gtest/gtest.h>

#include <set>
#include <string>
#include <vector>

#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/ros/common/params.h"

namespace swarm_transport {
namespace {

std::vector<TimedEvent> Read(const std::string& yaml, std::string* error) {
  XmlRpc::XmlRpcValue file;
  std::vector<TimedEvent> events;
  if (!XmlRpcFromYamlText(yaml, &file, error) || !EventsFromXmlRpc(file, &events, error)) {
    return {};
  }
  return events;
}

TEST(EventScheduleTest, ReadsEveryKind) {
  std::string error;
  const std::vector<TimedEvent> events = Read(
      "events:\n"
      "  - {tick: 5, kind: freeze, from: 0, to: 3}\n"
      "  - {tick: 9, kind: continue, from: 0, to: 3}\n"
      "  - {tick: 7, kind: kill, robot: 4}\n"
      "  - {tick: 2, kind: spawn, robot: 30, x: 1.5, y: 2, theta_deg: 90}\n"
      "  - {tick: 3, kind: object_update, mission: 7, x: 6.5, y: 7}\n"
      "  - {tick: 4, kind: signal, mission: 7, event: UNLOADED}\n"
      "  - {tick: 6, kind: statist, robot: 900, sub_id: 2, x: 8, y: 3}\n"
      "  - {tick: 8, kind: remove_statist, robot: 900, sub_id: 2}\n"
      "  - {tick: 10, kind: odom_stop, robot: 3, ticks: 20}\n",
      &error);
  ASSERT_EQ(events.size(), 9u) << error;
  EXPECT_EQ(events[8].kind, TimedEvent::Kind::kOdomStop);
  EXPECT_EQ(events[8].robot, 3);
  EXPECT_EQ(events[8].ticks, 20u);
  EXPECT_EQ(events[6].kind, TimedEvent::Kind::kStatist);
  EXPECT_EQ(events[6].sub_id, 2);
  EXPECT_EQ(events[7].kind, TimedEvent::Kind::kRemoveStatist);
  EXPECT_EQ(events[0].kind, TimedEvent::Kind::kFreeze);
  EXPECT_EQ(events[0].to, 3);
  EXPECT_EQ(events[2].robot, 4);
  EXPECT_DOUBLE_EQ(events[3].theta_deg, 90.0);
  EXPECT_EQ(events[4].mission, 7);
  EXPECT_DOUBLE_EQ(events[4].x, 6.5);
  EXPECT_EQ(events[5].signal, Mission_Event::UNLOADED);
}

TEST(EventScheduleTest, ABadEntryIsNamed) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"events:\n  - {tick: 5, kind: freeze, from: 3, to: 1}\n", "events[0]: 'from' and 'to'"},
      {"events:\n  - {tick: -1, kind: kill, robot: 1}\n", "events[0]: 'tick'"},
      {"events:\n  - {tick: 1, kind: dance}\n", "events[0]: needs 'kind'"},
      {"events:\n  - {tick: 1, kind: kill, robot: 1, x: 3}\n", "unknown key 'x'"},
      {"events:\n  - {tick: 1, kind: signal, mission: 7, event: GO}\n", "LOADED or UNLOADED"},
      {"events:\n  - {tick: 1, kind: spawn, robot: 3, x: .nan, y: 1}\n", "finite 'x', 'y'"},
      {"events:\n  - {tick: 1, kind: odom_stop, robot: 3, ticks: 0}\n", "'ticks', an integer"},
      {"events:\n  - {tick: 1, kind: odom_stop, robot: 3}\n", "'ticks', an integer"},
      {"things: []\n", "a list under the key 'events'"}};
  for (const auto& c : cases) {
    std::string error;
    EXPECT_TRUE(Read(c.first, &error).empty()) << c.first;
    EXPECT_NE(error.find(c.second), std::string::npos) << c.first << " -> " << error;
  }
}

TEST(EventScheduleTest, HandsOutEachEventOnceAtItsTick) {
  std::vector<TimedEvent> events(4);
  events[0].tick = 5;
  events[0].robot = 1;
  events[1].tick = 2;
  events[1].robot = 2;
  events[2].tick = 5;
  events[2].robot = 3;
  events[3].tick = 9;
  events[3].robot = 4;
  EventSchedule schedule(events);
  EXPECT_TRUE(schedule.Due(1).empty());
  ASSERT_EQ(schedule.Due(2).size(), 1u);
  const std::vector<TimedEvent> five = schedule.Due(5);
  ASSERT_EQ(five.size(), 2u);
  EXPECT_EQ(five[0].robot, 1);  // file order within a tick
  EXPECT_EQ(five[1].robot, 3);
  EXPECT_TRUE(schedule.Due(5).empty());
  EXPECT_FALSE(schedule.empty());
  EXPECT_EQ(schedule.Due(100).size(), 1u);  // a late tick takes what is overdue
  EXPECT_TRUE(schedule.empty());
}

TEST(EventScheduleTest, RobotsAtFollowsTheSpawnsAndKillsDueByThatTick) {
  std::string error;
  const std::vector<TimedEvent> events = Read(
      "events:\n"
      "  - {tick: 30, kind: kill, robot: 6}\n"
      "  - {tick: 10, kind: spawn, robot: 6, x: 1, y: 1}\n"
      "  - {tick: 10, kind: freeze, from: 0, to: 3}\n"
      "  - {tick: 20, kind: kill, robot: 0}\n"
      "  - {tick: 40, kind: spawn, robot: 6, x: 2, y: 2}\n",
      &error);
  ASSERT_EQ(error, "");
  const std::set<std::uint16_t> start = {0, 1, 2};
  EXPECT_EQ(RobotsAt(start, events, 0), start);
  EXPECT_EQ(RobotsAt(start, events, 9), start);
  EXPECT_EQ(RobotsAt(start, events, 10), (std::set<std::uint16_t>{0, 1, 2, 6}));  // due at 10
  EXPECT_EQ(RobotsAt(start, events, 25), (std::set<std::uint16_t>{1, 2, 6}));
  EXPECT_EQ(RobotsAt(start, events, 30), (std::set<std::uint16_t>{1, 2}));
  EXPECT_EQ(RobotsAt(start, events, 99), (std::set<std::uint16_t>{1, 2, 6}));
  EXPECT_EQ(RobotsAt(start, {}, 99), start);
}

}  // namespace
}  // namespace swarm_transport
