#include "swarm_transport/core/swarm_config.h"

#include <gtest/gtest.h>

#include <limits>
#include <string>

namespace swarm_transport {
namespace core {
namespace {

// The first bad key is named; the parts' own checks come first.
TEST(SwarmConfigTest, DefaultsAreValidAndEachBadKeyIsNamed) {
  EXPECT_EQ(SwarmConfig().Validate(), "");
  struct Case {
    void (*spoil)(SwarmConfig*);
    std::string names;
  };
  const Case cases[] = {
      {[](SwarmConfig* c) { c->tick_period_s = 0.0; }, "tick_period_s must be > 0 but is 0"},
      {[](SwarmConfig* c) { c->tick_period_s = std::numeric_limits<double>::infinity(); },
       "tick_period_s"},
      {[](SwarmConfig* c) { c->loaded_delay_s = std::numeric_limits<double>::quiet_NaN(); },
       "loaded_delay_s and unloaded_delay_s must be finite"},
      {[](SwarmConfig* c) { c->object_update_ticks = 0; },
       "object_update_ticks must be >= 1 but is 0"},
      {[](SwarmConfig* c) { c->chain_hops = 0; }, "chain_hops must be >= 1 but is 0"},
      {[](SwarmConfig* c) { c->leader.wait_fraction = 1.5; }, "wait_fraction"},
      {[](SwarmConfig* c) { c->flocking.local_range_m = -1.0; }, "local_range_m"},
      {[](SwarmConfig* c) { c->balloon.growth_m_per_tick = 0.0; },
       "balloon_growth_m_per_tick must be finite and > 0 but is 0"},
      {[](SwarmConfig* c) { c->loading_spread = static_cast<LoadingSpread>(7); },
       "loading_spread must be none or balloon but is 7"},
      {[](SwarmConfig* c) { c->loading_spread_ticks = 0; },
       "loading_spread_ticks must be in [1, 10000] but is 0"},
  };
  for (const Case& c : cases) {
    SwarmConfig config;
    c.spoil(&config);
    EXPECT_NE(config.Validate().find(c.names), std::string::npos)
        << "'" << config.Validate() << "' should name " << c.names;
  }
  SwarmConfig config;
  config.transport.transport_leader_weight = 0;
  EXPECT_NE(config.Validate(), "");
}

TEST(SwarmConfigTest, NegativeDelaysMeanWaitForASignalAndAreValid) {
  SwarmConfig config;
  config.loaded_delay_s = -1.0;
  config.unloaded_delay_s = -1.0;
  EXPECT_EQ(config.Validate(), "");
}

}  // namespace
}  // namespace core
}  // namespace swarm_transport
