// The one reader of a number in a parameter or a YAML file (XmlRpcNumber, params.h): an int or a
// double that is finite; a string, a bool, a list, NaN or an infinity is refused with a reason.
// And its users - the /swarm configuration, the missions file and the events file - refuse a
// non-finite number with an error naming the key, as they refuse a string.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "swarm_transport/ros/common/event_schedule.h"
#include "swarm_transport/ros/common/params.h"
#include "swarm_transport/ros/dispatcher/dispatcher_options.h"

namespace swarm_transport {
namespace {

constexpr double kUntouched = 12345.0;

TEST(XmlRpcNumberTest, AnIntIsANumber) {
  double out = kUntouched;
  std::string why;
  EXPECT_TRUE(XmlRpcNumber(XmlRpc::XmlRpcValue(7), &out, &why)) << why;
  EXPECT_EQ(out, 7.0);
  EXPECT_TRUE(XmlRpcNumber(XmlRpc::XmlRpcValue(-3), &out));
  EXPECT_EQ(out, -3.0);
}

TEST(XmlRpcNumberTest, AFiniteDoubleIsANumber) {
  double out = kUntouched;
  std::string why;
  EXPECT_TRUE(XmlRpcNumber(XmlRpc::XmlRpcValue(0.25), &out, &why)) << why;
  EXPECT_EQ(out, 0.25);
  EXPECT_TRUE(XmlRpcNumber(XmlRpc::XmlRpcValue(-1e300), &out, &why)) << why;
  EXPECT_EQ(out, -1e300);
}

// A refused value leaves `out` as it was and says why.
void ExpectRefused(const XmlRpc::XmlRpcValue& value, const std::string& reason) {
  const std::string shown = value.toXml();
  double out = kUntouched;
  std::string why;
  EXPECT_FALSE(XmlRpcNumber(value, &out, &why)) << shown;
  EXPECT_EQ(out, kUntouched) << shown;
  EXPECT_EQ(why, reason) << shown;
  EXPECT_FALSE(XmlRpcNumber(value, &out)) << "without a reason asked for: " << shown;
  EXPECT_EQ(out, kUntouched) << shown;
}

TEST(XmlRpcNumberTest, NanIsRefused) {
  ExpectRefused(XmlRpc::XmlRpcValue(std::numeric_limits<double>::quiet_NaN()),
                "must be finite but is nan");
}

TEST(XmlRpcNumberTest, AnInfinityIsRefused) {
  ExpectRefused(XmlRpc::XmlRpcValue(std::numeric_limits<double>::infinity()),
                "must be finite but is inf");
  ExpectRefused(XmlRpc::XmlRpcValue(-std::numeric_limits<double>::infinity()),
                "must be finite but is -inf");
}

TEST(XmlRpcNumberTest, AStringIsRefusedEvenWhenItSpellsANumber) {
  ExpectRefused(XmlRpc::XmlRpcValue(std::string("7")), "must be a number but is a string");
}

TEST(XmlRpcNumberTest, ABoolIsRefused) {
  ExpectRefused(XmlRpc::XmlRpcValue(true), "must be a number but is a bool");
}

TEST(XmlRpcNumberTest, AListAndNothingAreRefused) {
  XmlRpc::XmlRpcValue list;
  list[0] = 1.0;
  ExpectRefused(list, "must be a number but is a list");
  ExpectRefused(XmlRpc::XmlRpcValue(), "must be a number but is empty");
}

TEST(XmlRpcNumberTest, YamlSpellingsOfNonFiniteNumbersAreRefused) {
  for (const char* text : {"x: .nan", "x: .inf", "x: -.inf", "x: .NaN", "x: .Inf"}) {
    XmlRpc::XmlRpcValue dict;
    std::string error;
    ASSERT_TRUE(XmlRpcFromYamlText(text, &dict, &error)) << text << ": " << error;
    double out = kUntouched;
    EXPECT_FALSE(XmlRpcNumber(dict["x"], &out, &error)) << text;
    EXPECT_EQ(out, kUntouched) << text;
    EXPECT_EQ(error.rfind("must be finite but is ", 0), 0u) << text << " -> " << error;
  }
}

// The /swarm configuration: the same key as an int, a double, NaN, inf, a string and a bool.
TEST(XmlRpcNumberTest, TheSwarmConfigurationReadsNumbersThroughIt) {
  auto load = [](const std::string& yaml, SwarmConfig* config, std::string* error) {
    XmlRpc::XmlRpcValue dict;
    EXPECT_TRUE(XmlRpcFromYamlText(yaml, &dict, error)) << *error;
    return ConfigFromXmlRpc(dict, config, error);
  };
  SwarmConfig config;
  std::string error;
  ASSERT_TRUE(load("cohesion: 1", &config, &error)) << error;
  EXPECT_EQ(config.flocking.cohesion, 1.0);
  ASSERT_TRUE(load("cohesion: 0.5", &config, &error)) << error;
  EXPECT_EQ(config.flocking.cohesion, 0.5);
  const std::vector<std::pair<std::string, std::string>> refused = {
      {"cohesion: .nan", "parameter 'cohesion' must be finite but is nan"},
      {"cohesion: .inf", "parameter 'cohesion' must be finite but is inf"},
      {"cohesion: many", "parameter 'cohesion' must be a number but is a string"},
      {"cohesion: true", "parameter 'cohesion' must be a number but is a bool"},
      {"danger_zones: [{shape: circle, x: .nan, y: 1, radius: 1}]",
       "danger_zones[0]: a zone needs finite numbers x and y"},
      {"danger_zones: [{shape: circle, x: 1, y: 1, radius: .inf}]",
       "danger_zones[0]: a circle zone needs radius > 0"},
      {"danger_zones: [{shape: rect, x: 1, y: 1, size_x: 1, size_y: .nan}]",
       "danger_zones[0]: a rect zone needs size_x > 0 and size_y > 0"}};
  for (const auto& c : refused) {
    SwarmConfig before;
    SwarmConfig loaded = before;
    EXPECT_FALSE(load(c.first, &loaded, &error)) << c.first;
    EXPECT_EQ(error.rfind(c.second, 0), 0u) << c.first << " -> " << error;
    EXPECT_EQ(loaded.flocking.cohesion, before.flocking.cohesion) << c.first;
  }
}

// A missions file: target and object take ints and doubles, and refuse NaN and inf.
TEST(XmlRpcNumberTest, TheMissionsFileReadsNumbersThroughIt) {
  auto read = [](const std::string& entry, std::vector<core::MissionSpec>* missions,
                 std::string* error) {
    XmlRpc::XmlRpcValue file;
    EXPECT_TRUE(XmlRpcFromYamlText("missions:\n  - " + entry + "\n", &file, error)) << *error;
    return MissionsFromXmlRpc(file, missions, error);
  };
  std::vector<core::MissionSpec> missions;
  std::string error;
  ASSERT_TRUE(read("{id: 1, robot_ids: [0], leaders: 1, target: [2, 2.5], object: [1, 1, 0.5, 1]}",
                   &missions, &error))
      << error;
  ASSERT_EQ(missions.size(), 1u);
  EXPECT_EQ(missions[0].target.x, 2.0);
  EXPECT_EQ(missions[0].target.y, 2.5);
  EXPECT_EQ(missions[0].object_size.x, 0.5);
  for (const std::string entry : {"{id: 1, robot_ids: [0], leaders: 1, target: [.nan, 2]}",
                                  "{id: 1, robot_ids: [0], leaders: 1, target: [2, .inf]}",
                                  "{id: 1, robot_ids: [0], leaders: 1, target: ['2', 2]}",
                                  "{id: 1, robot_ids: [0], leaders: 1, target: [true, 2]}"}) {
    EXPECT_FALSE(read(entry, &missions, &error)) << entry;
    EXPECT_EQ(error.rfind("missions[0]: 'target' must be [x, y], finite numbers", 0), 0u)
        << entry << " -> " << error;
  }
  EXPECT_FALSE(read("{id: 1, robot_ids: [0], leaders: 1, target: [2, 2], object: [1, -.inf, 1, 1]}",
                    &missions, &error));
  EXPECT_EQ(error.rfind("missions[0]: 'object' must be [x, y, size_x, size_y], finite", 0), 0u)
      << error;
}

// An events file: tick, x and y take ints and doubles, and refuse NaN and inf.
TEST(XmlRpcNumberTest, TheEventsFileReadsNumbersThroughIt) {
  auto read = [](const std::string& entry, std::vector<TimedEvent>* events, std::string* error) {
    XmlRpc::XmlRpcValue file;
    EXPECT_TRUE(XmlRpcFromYamlText("events:\n  - " + entry + "\n", &file, error)) << *error;
    return EventsFromXmlRpc(file, events, error);
  };
  std::vector<TimedEvent> events;
  std::string error;
  ASSERT_TRUE(read("{tick: 4.0, kind: spawn, robot: 3, x: 1, y: 2.5}", &events, &error)) << error;
  ASSERT_EQ(events.size(), 1u);
  EXPECT_EQ(events[0].tick, 4u);
  EXPECT_EQ(events[0].x, 1.0);
  EXPECT_EQ(events[0].y, 2.5);
  for (const std::string entry : {"{tick: 1, kind: spawn, robot: 3, x: 1, y: .nan}",
                                  "{tick: 1, kind: spawn, robot: 3, x: -.inf, y: 1}",
                                  "{tick: 1, kind: spawn, robot: 3, x: one, y: 1}",
                                  "{tick: 1, kind: spawn, robot: 3, x: false, y: 1}"}) {
    EXPECT_FALSE(read(entry, &events, &error)) << entry;
    EXPECT_EQ(error, "events[0]: a spawn needs 'robot' and finite 'x', 'y' (and 'theta_deg')")
        << entry;
  }
  EXPECT_FALSE(read("{tick: .inf, kind: kill, robot: 1}", &events, &error));
  EXPECT_EQ(error, "events[0]: 'tick' must be an integer >= 0");
}

}  // namespace
}  // namespace swarm_transport
