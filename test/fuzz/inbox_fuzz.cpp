// A robot's inbox in any order with any values: freeze / continue ranges, orders, object updates
// and deletes, signals, statuses, live flocking tunings, ticks. No crash, no sanitizer report,
// and a finite command on finite positions; a rejected message leaves the robot's state as it
// was (checked for freeze / continue: an inverted range changes nothing; for a tuning: the
// flocking parameters in use stay, an accepted one is used as given).
#include <cmath>
#include <limits>

#include "fuzz_common.h"
#include "swarm_transport/core/robot_brain.h"
#include "swarm_transport/ros/common/conversions.h"

using namespace swarm_transport;  // NOLINT

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  FuzzedDataProvider in(data, size);
  const core::SwarmConfig config;
  const std::uint16_t id = in.ConsumeIntegralInRange<std::uint16_t>(0, 5);
  core::RobotBrain brain(id, config);
  const std::set<std::uint16_t> known = fuzz::KnownRobots(8);
  std::uint64_t tick = 0;
  while (in.remaining_bytes() > 0) {
    switch (in.ConsumeIntegralInRange<int>(0, 8)) {
      case 0:
      case 1: {
        const std::uint16_t from = in.ConsumeIntegralInRange<std::uint16_t>(0, 10);
        const std::uint16_t to = in.ConsumeIntegralInRange<std::uint16_t>(0, 10);
        const bool was = brain.frozen();
        const bool freeze = in.ConsumeBool();
        const std::string why =
            freeze ? brain.Take(core::Freeze{from, to}) : brain.Take(core::Continue{from, to});
        fuzz::Require(why.empty() == (from < to));
        if (!why.empty()) fuzz::Require(brain.frozen() == was);
        break;
      }
      case 2: {
        core::MissionTaken taken;
        brain.Take(ToMissionSpec(fuzz::AnyOrder(&in)), known, &taken);
        break;
      }
      case 3:
        brain.Take(core::ObjectUpdate{in.ConsumeIntegralInRange<std::uint16_t>(0, 5),
                                      {fuzz::AnyFloat(&in), fuzz::AnyFloat(&in)}});
        break;
      case 4:
        brain.Take(core::ObjectDelete{in.ConsumeIntegralInRange<std::uint16_t>(0, 5)});
        break;
      case 5:
        brain.Take(
            core::Signal{in.ConsumeIntegralInRange<std::uint16_t>(0, 5),
                         static_cast<core::MissionEventKind>(in.ConsumeIntegral<std::uint8_t>()),
                         in.ConsumeIntegral<std::uint64_t>()});
        break;
      case 6: {
        core::PhaseStatus status;
        status.mission_id = in.ConsumeIntegralInRange<std::uint16_t>(0, 5);
        status.phase = static_cast<core::MissionPhase>(in.ConsumeIntegral<std::uint8_t>());
        // The robots its first leader counts lost: any ids, the robot itself among them.
        const int lost = in.ConsumeIntegralInRange<int>(0, 3);
        for (int k = 0; k < lost; ++k) {
          status.lost.push_back(in.ConsumeIntegralInRange<std::uint16_t>(0, 12));
        }
        brain.Take(status);
        break;
      }
      case 7: {
        // Any value, NaN and infinities included.
        const auto any = [&in]() -> double {
          switch (in.ConsumeIntegralInRange<int>(0, 3)) {
            case 0:
              return std::numeric_limits<double>::quiet_NaN();
            case 1:
              return in.ConsumeBool() ? std::numeric_limits<double>::infinity()
                                      : -std::numeric_limits<double>::infinity();
            default:
              return fuzz::AnyFloat(&in);
          }
        };
        core::FlockingTuning t;
        t.free_will_deg = any();
        t.cohesion = any();
        t.local_range_m = any();
        t.speed_m_per_tick = any();
        const core::FlockingTuning before = brain.tuning();
        const std::string why = brain.OnTuning(t);
        fuzz::Require(why.empty() ? brain.tuning() == t : brain.tuning() == before);
        break;
      }
      default: {
        core::Perception p;
        p.self.position = {in.ConsumeFloatingPointInRange<double>(0.05, 11.0),
                           in.ConsumeFloatingPointInRange<double>(0.05, 11.0)};
        p.self.heading = core::Angle(in.ConsumeFloatingPointInRange<double>(-720.0, 720.0));
        const std::size_t n = in.ConsumeIntegralInRange<std::size_t>(0, 8);
        for (std::size_t k = 0; k < n; ++k) {
          core::Neighbour other;
          other.id = in.ConsumeIntegralInRange<std::uint16_t>(0, 9);
          other.sub_id = in.ConsumeIntegralInRange<std::uint8_t>(0, 2);
          other.type = in.ConsumeIntegralInRange<std::uint8_t>(0, 2);
          other.position = {in.ConsumeFloatingPointInRange<double>(0.05, 11.0),
                            in.ConsumeFloatingPointInRange<double>(0.05, 11.0)};
          other.heading = core::Angle(in.ConsumeFloatingPointInRange<double>(0.0, 360.0));
          p.others.push_back(other);
        }
        tick += in.ConsumeIntegralInRange<std::uint64_t>(0, 30);
        const core::BrainTick step = brain.Tick(p, tick, in.ConsumeBool());
        fuzz::Require(std::isfinite(step.command.linear) && std::isfinite(step.command.angular));
        break;
      }
    }
  }
  return 0;
}
