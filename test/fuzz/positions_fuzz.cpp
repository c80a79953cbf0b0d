// Positions as any node may announce them on /flock/position (virtual copies, statists, any
// type, any value) through the simulator's relay and the radio to a robot's perception: bad ones
// are refused, the rest never make the radio or a robot produce a non-finite value.
#include <cmath>
#include <vector>

#include "fuzz_common.h"
#include "swarm_transport/core/random.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/sim/lockstep_engine.h"
#include "swarm_transport/sim/mission_relay.h"
#include "swarm_transport/sim/radio.h"
#include "swarm_transport/sim/world2d.h"

using namespace swarm_transport;  // NOLINT

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  sim::WorldParams params;
  sim::World2D world(params);
  std::string error;
  const int robots = in.ConsumeIntegralInRange<int>(1, 6);
  for (int i = 0; i < robots; ++i) {
    world.Spawn(static_cast<std::uint16_t>(i),
                {{in.ConsumeFloatingPointInRange<double>(0.1, 10.9),
                  in.ConsumeFloatingPointInRange<double>(0.1, 10.9)},
                 core::Angle(0.0)},
                &error);
  }
  sim::RelayedPositions relayed;
  const int announced = in.ConsumeIntegralInRange<int>(0, 8);
  for (int k = 0; k < announced; ++k) {
    core::Position p;
    p.robot_id = in.ConsumeIntegralInRange<std::uint16_t>(0, 8);
    p.sub_id = in.ConsumeIntegralInRange<std::uint8_t>(0, 3);
    p.type = in.ConsumeIntegralInRange<std::uint8_t>(0, 4);
    p.x = fuzz::AnyFloat(&in);
    p.y = fuzz::AnyFloat(&in);
    p.angle_deg = fuzz::AnyFloat(&in);
    const bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.angle_deg);
    const std::size_t before = relayed.size();
    const std::string why = relayed.Take(p);
    if (!finite || p.type > 2) fuzz::Require(!why.empty() || p.type == 0);
    if (!why.empty()) fuzz::Require(relayed.size() == before);
    if (in.ConsumeBool()) relayed.Erase(p.robot_id, p.sub_id);
    if (in.ConsumeBool()) relayed.EraseCopiesOf(in.ConsumeIntegralInRange<std::uint16_t>(0, 8));
  }
  core::Rng rng(1, sim::kRadioLossStream);
  sim::RadioParams radio_params;
  radio_params.hops = in.ConsumeIntegralInRange<int>(1, 4);
  radio_params.loss = in.ConsumeFloatingPointInRange<double>(0.0, 1.0);
  sim::Radio radio(radio_params, &rng);
  sim::LiveMissions missions;
  sim::LockstepEngine engine(&world, &radio, &missions);
  engine.BeginRound(0, 0.0, &relayed, {});
  core::Round round;
  for (std::size_t i = 0; i < world.size(); ++i) {
    engine.Round(i, false, &round);
    const core::Perception p = core::PerceptionOf(world.robots().nth(i)->first, round);
    for (const core::Neighbour& n : p.others) {
      fuzz::Require(std::isfinite(n.position.x) && std::isfinite(n.position.y));
    }
  }
  return 0;
}
