// Every rule of every core parameter validator (FlockingParams, LeaderParams, TransportParams,
// BalloonParams, SelectionParams, SwarmConfig, sim::WorldParams): a valid baseline passes, and
// each violation - both sides of a range, NaN and infinity where the rule asks for a finite
// number - gives an error that names the field.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "swarm_transport/core/assignment.h"
#include "swarm_transport/core/balloon.h"
#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/leader.h"
#include "swarm_transport/core/swarm_config.h"
#include "swarm_transport/core/transport.h"
#include "swarm_transport/sim/world2d.h"
#include "validator_fixture.h"

namespace swarm_transport {
namespace {

using namespace validator_testing;  // NOLINT: the fixture of every validator test

TEST(ValidatorsTest, FlockingParams) {
  using P = core::FlockingParams;
  std::vector<Violation<P>> v;
  AddRange<P>(&v, "local_range_m", &P::local_range_m, {0.0, -1.0, kNan, kInf});
  // speed must stay in (0, local_range_m)
  AddRange<P>(&v, "speed_m_per_tick", &P::speed_m_per_tick, {0.0, -0.1, 1.0, 2.0, kNan, kInf});
  AddRange<P>(&v, "free_will_deg", &P::free_will_deg, {-0.1, 360.1, kNan, kInf});
  AddRange<P>(&v, "cohesion", &P::cohesion, {-1.01, 1.01, kNan, -kInf});
  AddRange<P>(&v, "robot_radius_m", &P::robot_radius_m, {0.0, -0.05, kNan, kInf});
  AddRange<P>(&v, "collision_margin", &P::collision_margin, {-0.01, kNan, kInf});
  // world_size_m > 4 * robot_radius_m (0.2 with the default radius)
  AddRange<P>(&v, "world_size_m", &P::world_size_m, {0.2, 0.0, kNan, kInf});
  AddRange<P>(&v, "speed_reduction", &P::speed_reduction, {0.0, 1.0, kNan});
  AddRange<P>(&v, "zone_margin_m", &P::zone_margin_m, {-0.01, kNan, kInf});
  v.push_back({"speed_retries = -1", [](P* p) { p->speed_retries = -1; }, "speed_retries"});
  ExpectEachViolationNamed(P(), v);

  // The bounds themselves.
  P p;
  p.free_will_deg = 0.0;
  p.cohesion = -1.0;
  p.collision_margin = 0.0;
  p.zone_margin_m = 0.0;
  p.speed_retries = 0;
  EXPECT_EQ(p.Validate(), "");
  p.free_will_deg = 360.0;
  p.cohesion = 1.0;
  EXPECT_EQ(p.Validate(), "");
}

TEST(ValidatorsTest, LeaderParams) {
  using P = core::LeaderParams;
  std::vector<Violation<P>> v;
  AddRange<P>(&v, "goal_tolerance_m", &P::goal_tolerance_m, {0.0, -0.1, kNan, kInf});
  AddRange<P>(&v, "wait_fraction", &P::wait_fraction, {0.0, 1.01, kNan});
  for (int bad : {0, 256}) {
    v.push_back({"virtual_copies = " + std::to_string(bad),
                 [bad](P* p) { p->virtual_copies = bad; }, "leader_virtual_copies"});
  }
  v.push_back({"swerve_after_blocked_ticks = -1", [](P* p) { p->swerve_after_blocked_ticks = -1; },
               "leader_swerve_after_blocked_ticks"});
  ExpectEachViolationNamed(P(), v);

  P p;
  p.wait_fraction = 1.0;
  p.virtual_copies = 255;
  p.swerve_after_blocked_ticks = 0;
  EXPECT_EQ(p.Validate(), "");
}

TEST(ValidatorsTest, TransportParams) {
  using P = core::TransportParams;
  std::vector<Violation<P>> v;
  v.push_back(
      {"replan_period_ticks = 0", [](P* p) { p->replan_period_ticks = 0; }, "replan_period"});
  AddRange<P>(&v, "planner_turn_deg_per_tick", &P::planner_turn_deg_per_tick,
              {0.0, -1.0, kNan, kInf});
  AddRange<P>(&v, "lookahead", &P::lookahead, {0.99, kNan, kInf});
  AddRange<P>(&v, "passive_slowdown", &P::passive_slowdown, {0.0, 1.0, kNan});
  v.push_back({"passive_tries = -1", [](P* p) { p->passive_tries = -1; }, "passive_tries"});
  AddRange<P>(&v, "leader_slowdown", &P::leader_slowdown, {0.0, 1.0, kNan});
  v.push_back({"leader_tries = -1", [](P* p) { p->leader_tries = -1; }, "leader_tries"});
  for (int bad : {0, 256}) {
    v.push_back({"transport_leader_weight = " + std::to_string(bad),
                 [bad](P* p) { p->transport_leader_weight = bad; }, "transport_leader_weight"});
  }
  AddRange<P>(&v, "leader_reach_m", &P::leader_reach_m, {-0.01, kNan, kInf});
  AddRange<P>(&v, "approach_radius_m", &P::approach_radius_m, {-0.01, kNan, kInf});
  AddRange<P>(&v, "formation_slack_m", &P::formation_slack_m, {-0.01, kNan, kInf});
  AddRange<P>(&v, "formation_speed_fraction", &P::formation_speed_fraction, {0.0, 1.01, kNan});
  ExpectEachViolationNamed(P(), v);

  P p;
  p.lookahead = 1.0;
  p.passive_tries = 0;
  p.leader_tries = 0;
  p.transport_leader_weight = 255;
  p.formation_speed_fraction = 1.0;
  p.formation_slack_m = 0.0;
  EXPECT_EQ(p.Validate(), "");
}

TEST(ValidatorsTest, BalloonParams) {
  using P = core::BalloonParams;
  std::vector<Violation<P>> v;
  AddRange<P>(&v, "balloon_growth_m_per_tick", &P::growth_m_per_tick, {0.0, -0.1, kNan, kInf});
  ExpectEachViolationNamed(P(), v);
}

TEST(ValidatorsTest, SelectionParams) {
  using P = core::SelectionParams;
  std::vector<Violation<P>> v;
  AddRange<P>(&v, "speed", &P::speed_m, {0.0, -0.1, kNan, kInf});
  AddRange<P>(&v, "turn", &P::turn_deg, {0.0, -1.0, kNan, kInf});
  AddRange<P>(&v, "corridor_m", &P::corridor_m, {-0.01, kNan, kInf});
  AddRange<P>(&v, "meet_tolerance", &P::meet_tolerance, {-0.01, kNan, kInf});
  AddRange<P>(&v, "crossing_wait", &P::crossing_wait, {kNan, kInf, -kInf});
  AddRange<P>(&v, "settled_clear", &P::settled_clear, {kNan, kInf, -kInf});
  v.push_back({"max_rounds = 0", [](P* p) { p->max_rounds = 0; }, "max_rounds"});
  v.push_back({"max_rounds = 2", [](P* p) { p->max_rounds = 2; }, "max_rounds"});
  ExpectEachViolationNamed(P(), v);

  P p;
  p.corridor_m = 0.0;
  p.meet_tolerance = 0.0;
  p.crossing_wait = -5.0;  // <= 0: the default wait
  p.settled_clear = -1.0;  // < 0: corridor_m / speed_m
  p.max_rounds = 3;        // the least that the freezing rule needs
  EXPECT_EQ(p.Validate(), "");
}

TEST(ValidatorsTest, SwarmConfig) {
  using P = core::SwarmConfig;
  std::vector<Violation<P>> v;
  // The parts' own rules come through (one each; the parts' tests above have them all).
  v.push_back({"flocking", [](P* p) { p->flocking.cohesion = 2.0; }, "cohesion"});
  v.push_back({"leader", [](P* p) { p->leader.wait_fraction = 0.0; }, "wait_fraction"});
  v.push_back({"transport", [](P* p) { p->transport.leader_tries = -1; }, "leader_tries"});
  v.push_back(
      {"balloon", [](P* p) { p->balloon.growth_m_per_tick = 0.0; }, "balloon_growth_m_per_tick"});
  AddRange<P>(&v, "tick_period_s", &P::tick_period_s, {0.0, -0.1, kNan, kInf});
  for (double bad : {kNan, kInf, -kInf}) {
    v.push_back({"loaded_delay_s = " + std::to_string(bad),
                 [bad](P* p) { p->loaded_delay_s = bad; }, "loaded_delay_s"});
    v.push_back({"unloaded_delay_s = " + std::to_string(bad),
                 [bad](P* p) { p->unloaded_delay_s = bad; }, "unloaded_delay_s"});
  }
  v.push_back(
      {"object_update_ticks = 0", [](P* p) { p->object_update_ticks = 0; }, "object_update_ticks"});
  v.push_back({"chain_hops = 0", [](P* p) { p->chain_hops = 0; }, "chain_hops"});
  AddRange<P>(&v, "lost_after_s", &P::lost_after_s, {0.0, -1.0, kNan, kInf});
  for (int bad : {-1, 65536}) {
    v.push_back({"mission_min_robots = " + std::to_string(bad),
                 [bad](P* p) { p->mission_min_robots = bad; }, "mission_min_robots"});
  }
  for (int bad : {0, 65536}) {
    v.push_back({"max_live_missions = " + std::to_string(bad),
                 [bad](P* p) { p->max_live_missions = bad; }, "max_live_missions"});
  }
  v.push_back({"loading_spread = 7",
               [](P* p) { p->loading_spread = static_cast<core::LoadingSpread>(7); },
               "loading_spread"});
  for (int bad : {0, 10001}) {
    v.push_back({"loading_spread_ticks = " + std::to_string(bad),
                 [bad](P* p) { p->loading_spread_ticks = bad; }, "loading_spread_ticks"});
  }
  ExpectEachViolationNamed(P(), v);

  P p;
  p.loaded_delay_s = -1.0;  // < 0: wait for a signal
  p.mission_min_robots = 65535;
  p.max_live_missions = 65535;
  p.loading_spread = core::LoadingSpread::kBalloon;
  p.loading_spread_ticks = 10000;
  EXPECT_EQ(p.Validate(), "");
}

TEST(ValidatorsTest, WorldParams) {
  using P = sim::WorldParams;
  std::vector<Violation<P>> v;
  AddRange<P>(&v, "world_size_m", &P::world_size_m, {0.0, -1.0, kNan, kInf});
  // robot_radius_m in (0, world_size_m / 2)
  AddRange<P>(&v, "robot_radius_m", &P::robot_radius_m, {0.0, -0.05, 11.088889 / 2, kNan, kInf});
  AddRange<P>(&v, "integration_step_s", &P::integration_step_s, {0.0, -0.01, kNan, kInf});
  AddRange<P>(&v, "command_duration_s", &P::command_duration_s, {0.0, -1.0, kNan, kInf});
  ExpectEachViolationNamed(P(), v);
}

}  // namespace
}  // namespace swarm_transport
