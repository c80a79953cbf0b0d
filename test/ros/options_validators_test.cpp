// Every rule of every node's options validator (SimulatorParams, DispatcherOptions,
// RecorderParams, RobotNodeOptions, RobotHostOptions): a valid baseline passes, and each
// violation - both sides of a range, NaN and infinity where the rule asks for a finite number -
// gives an error that names the parameter.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "../core/validator_fixture.h"
#include "swarm_transport/ros/bases/bases.h"
#include "swarm_transport/ros/dispatcher/dispatcher_options.h"
#include "swarm_transport/ros/recorder/recorder.h"
#include "swarm_transport/ros/robot/robot_host.h"
#include "swarm_transport/ros/robot/robot_node.h"
#include "swarm_transport/ros/simulator/simulator_params.h"

namespace swarm_transport {
namespace {

using namespace validator_testing;  // NOLINT: the fixture of every validator test

TEST(OptionsValidatorsTest, SimulatorParams) {
  using P = SimulatorParams;
  std::vector<Violation<P>> v;
  v.push_back(
      {"a bad /swarm key", [](P* p) { p->swarm.flocking.cohesion = 3.0; }, "/swarm: cohesion"});
  Add<P, double>(&v, "/swarm/radio_loss", &P::radio_loss, {-0.01, 1.01, kNan, kInf});
  v.push_back({"placement file without a file",
               [](P* p) {
                 p->placement = core::Placement::kFile;
                 p->placement_file.clear();
               },
               "~placement_file"});
  Add<P, int>(&v, "~robots", &P::robots, {-1, 65537});
  Add<P, double>(&v, "~lockstep_timeout_s", &P::lockstep_timeout_s, {0.0, -1.0, kNan, kInf});
  Add<P, int>(&v, "~lockstep_max_ticks", &P::lockstep_max_ticks, {-1});
  Add<P, int>(&v, "~lockstep_observers", &P::lockstep_observers, {-1});
  Add<P, double>(&v, "~lockstep_start_timeout_s", &P::lockstep_start_timeout_s, {-0.1, kNan, kInf});
  Add<P, double>(&v, "~real_time_factor", &P::real_time_factor, {-0.1, kNan, kInf});
  Add<P, int>(&v, "~hold_at", &P::hold_at, {-1});
  // ~integration_step_s in (0, tick_period_s = 0.1]
  Add<P, double>(&v, "~integration_step_s", &P::integration_step_s, {0.0, -0.01, 0.11, kNan, kInf});
  Add<P, double>(&v, "~markers_rate_hz", &P::markers_rate_hz, {-1.0, kNan, kInf});
  Add<P, double>(&v, "~radio_range_m", &P::radio_range_m, {0.0, -1.0, kNan, kInf});
  Add<P, int>(&v, "~trail_ticks", &P::trail_ticks, {-1, 10001});
  ExpectEachViolationNamed(P(), v);

  // The bounds and the exceptions.
  P p;
  p.radio_loss = 1.0;
  p.robots = 65536;
  p.lockstep_start_timeout_s = 0.0;
  p.markers_rate_hz = 0.0;
  p.integration_step_s = p.swarm.tick_period_s;
  p.trail_ticks = 10000;
  EXPECT_EQ(p.Validate(), "");
  p.placement = core::Placement::kFile;
  p.placement_file = "robots.txt";
  p.robots = -1;  // with a placement file: every line of it
  EXPECT_EQ(p.Validate(), "");
  p.robots = -2;
  EXPECT_NE(p.Validate().find("~robots"), std::string::npos) << p.Validate();
}

TEST(OptionsValidatorsTest, DispatcherOptions) {
  using P = DispatcherOptions;
  std::vector<Violation<P>> v;
  Add<P, double>(&v, "loaded_delay_s", &P::loaded_delay_s, {kNan, kInf, -kInf});
  Add<P, double>(&v, "unloaded_delay_s", &P::unloaded_delay_s, {kNan, kInf, -kInf});
  Add<P, double>(&v, "~start_delay_s", &P::start_delay_s, {-0.1, kNan, kInf});
  Add<P, int>(&v, "~max_live_missions", &P::max_live_missions, {0, 65536});
  Add<P, int>(&v, "~silent_abort_ticks", &P::silent_abort_ticks, {-1});
  ExpectEachViolationNamed(P(), v);

  P p;
  p.loaded_delay_s = -1.0;  // < 0: never sent
  p.unloaded_delay_s = -1.0;
  p.start_delay_s = 0.0;
  p.max_live_missions = 65535;
  p.silent_abort_ticks = 0;
  EXPECT_EQ(p.Validate(), "");
}

TEST(OptionsValidatorsTest, RecorderParams) {
  using P = RecorderParams;
  std::vector<Violation<P>> v;
  Add<P, double>(&v, "~sample_period_s", &P::sample_period_s, {0.0, -1.0, kNan, kInf});
  for (const std::string bad : {"", ".", "..", "a/b", "a,b", "a\"b", "a\nb", "a\rb"}) {
    v.push_back({"run_name '" + bad + "'", [bad](P* p) { p->run_name = bad; }, "~run_name"});
  }
  ExpectEachViolationNamed(P(), v);

  P p;
  p.run_name = "run.2 with spaces";
  EXPECT_EQ(p.Validate(), "");
}

TEST(OptionsValidatorsTest, RobotNodeOptions) {
  using P = RobotNodeOptions;
  P baseline;
  baseline.id = 0;
  std::vector<Violation<P>> v;
  Add<P, int>(&v, "~id", &P::id, {-1, 65536});
  v.push_back({"hardware in lock-step",
               [](P* p) {
                 p->hardware = true;
                 p->clock = core::Clock::kLockstep;
               },
               "~hardware needs ~clock realtime"});
  v.push_back({"hardware with broadcast comm",
               [](P* p) {
                 p->hardware = true;
                 p->comm = core::Comm::kBroadcast;
               },
               "~hardware needs ~comm local"});
  ExpectEachViolationNamed(baseline, v);
  EXPECT_NE(P().Validate().find("~id"), std::string::npos) << "~id is required";
  baseline.id = 65535;
  EXPECT_EQ(baseline.Validate(), "");
}

TEST(OptionsValidatorsTest, BasesParams) {
  using P = BasesParams;
  std::vector<Violation<P>> v;
  v.push_back(
      {"a bad /swarm key", [](P* p) { p->swarm.flocking.cohesion = 3.0; }, "/swarm: cohesion"});
  Add<P, int>(&v, "~robots", &P::robots, {-1, 65536});
  v.push_back({"placement file without a file", [](P* p) { p->placement = core::Placement::kFile; },
               "~placement_file"});
  Add<P, double>(&v, "~odom_rate_hz", &P::odom_rate_hz, {0.0, -1.0, 1001.0, kNan, kInf});
  Add<P, double>(&v, "~integration_step_s", &P::integration_step_s, {0.0, 0.2, kNan});
  v.push_back({"no fixed frame", [](P* p) { p->fixed_frame.clear(); }, "~fixed_frame"});
  v.push_back(
      {"negative noise", [](P* p) { p->noise.position_noise_m = -0.1; }, "~position_noise_m"});
  ExpectEachViolationNamed(P(), v);
}

TEST(OptionsValidatorsTest, RobotHostOptions) {
  using P = RobotHostOptions;
  P baseline;
  baseline.from = 0;
  baseline.to = 5;
  std::vector<Violation<P>> v;
  Add<P, int>(&v, "~from", &P::from, {-1, 65536});
  // ~to in (~from, 65536]
  Add<P, int>(&v, "~to", &P::to, {0, -1, 65537});
  Add<P, int>(&v, "~threads", &P::threads, {0, 65});
  for (core::Deploy bad : {core::Deploy::kProcess, core::Deploy::kNone}) {
    v.push_back({std::string("deploy ") + core::DeployName(bad), [bad](P* p) { p->deploy = bad; },
                 "~deploy"});
  }
  ExpectEachViolationNamed(baseline, v);

  P p = baseline;
  p.from = 65535;
  p.to = 65536;
  p.threads = 64;
  p.deploy = core::Deploy::kHostSim;
  EXPECT_EQ(p.Validate(), "");
  p.to = p.from;  // an empty range
  EXPECT_NE(p.Validate().find("~to"), std::string::npos) << p.Validate();
}

}  // namespace
}  // namespace swarm_transport
