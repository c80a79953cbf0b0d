// The simulated world under any sequence of spawns, kills, teleports, commands and steps with
// any values (what /spawn, teleport services and cmd_vel may carry): rejected inputs change
// nothing, and every robot always stays inside the arena with a finite pose.
#include <cmath>

#include "fuzz_common.h"
#include "swarm_transport/sim/world2d.h"

using namespace swarm_transport;  // NOLINT

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  sim::WorldParams params;
  params.world_size_m = in.ConsumeFloatingPointInRange<double>(0.5, 20.0);
  params.robot_radius_m = in.ConsumeFloatingPointInRange<double>(0.01, 0.2);
  params.integration_step_s = in.ConsumeFloatingPointInRange<double>(0.001, 0.2);
  params.command_duration_s = in.ConsumeFloatingPointInRange<double>(0.01, 2.0);
  if (!params.Validate().empty()) return 0;
  sim::World2D world(params);
  std::string error;
  while (in.remaining_bytes() > 0) {
    const std::uint16_t id = in.ConsumeIntegralInRange<std::uint16_t>(0, 6);
    switch (in.ConsumeIntegralInRange<int>(0, 5)) {
      case 0:
        world.Spawn(id,
                    {{fuzz::AnyFloat(&in), fuzz::AnyFloat(&in)}, core::Angle(fuzz::AnyFloat(&in))},
                    &error);
        break;
      case 1:
        world.Kill(id, &error);
        break;
      case 2:
        world.TeleportAbsolute(
            id, {{fuzz::AnyFloat(&in), fuzz::AnyFloat(&in)}, core::Angle(fuzz::AnyFloat(&in))},
            &error);
        break;
      case 3:
        world.TeleportRelative(id, fuzz::AnyFloat(&in), fuzz::AnyFloat(&in), &error);
        break;
      case 4: {
        core::Velocity v;
        v.linear = in.ConsumeFloatingPointInRange<double>(-5.0, 5.0);
        v.angular = in.ConsumeFloatingPointInRange<double>(-10.0, 10.0);
        world.SetCommand(id, v, &error);
        break;
      }
      default:
        world.Step(in.ConsumeFloatingPointInRange<double>(0.0, 1.0));
        break;
    }
    for (const auto& entry : world.robots()) {
      const core::Vec2 p = entry.second.pose.position;
      fuzz::Require(std::isfinite(p.x) && std::isfinite(p.y));
      fuzz::Require(p.x >= -1e-9 && p.y >= -1e-9 && p.x <= params.world_size_m + 1e-9 &&
                    p.y <= params.world_size_m + 1e-9);
    }
  }
  return 0;
}
