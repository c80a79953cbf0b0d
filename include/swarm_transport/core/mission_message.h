// One mission message as a robot takes it in, whatever carried it: a lock-step round (the
// relay), a topic (real time), a host's shared subscription or a fuzzer. RobotBrain::Take is
// the one inbox; the ROS side only converts (ros/common/conversions.h). A new kind of mission
// message is a new alternative here, its message and conversion, and its case in
// RobotBrain::Take; the relay, the rounds and the answers carry it as it is.
#ifndef SWARM_TRANSPORT_CORE_MISSION_MESSAGE_H_
#define SWARM_TRANSPORT_CORE_MISSION_MESSAGE_H_

#include <cstdint>
#include <variant>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/mission.h"

namespace swarm_transport {
namespace core {

// ObjectUpdate: the first leader's (or the dispatcher's) new centre of a mission's object.
struct ObjectUpdate {
  std::uint16_t mission_id = 0;
  Vec2 centre;
};

// ObjectDelete: the mission's object is gone.
struct ObjectDelete {
  std::uint16_t mission_id = 0;
};

// Freeze / Continue: robots with ids in [from, to) stop driving / drive again.
struct Freeze {
  std::uint16_t from = 0;
  std::uint16_t to = 0;
};
struct Continue {
  std::uint16_t from = 0;
  std::uint16_t to = 0;
};

// Signal: the dispatcher's (or a user's) LOADED / UNLOADED, not applied before a tick.
// `kind` is the message's raw value (the brain rejects anything but kLoaded and kUnloaded).
struct Signal {
  std::uint16_t mission_id = 0;
  MissionEventKind kind = MissionEventKind::kLoaded;
  std::uint64_t not_before_tick = 0;
};

// PhaseStatus: a mission's phase as its first leader (or the dispatcher) published it; a
// value beyond kRejected is no phase and ignored. `lost`: the robots of the mission its first
// leader counts lost (ascending; the dispatcher's and a relay's standing phase: none).
struct PhaseStatus {
  std::uint16_t mission_id = 0;
  MissionPhase phase = MissionPhase::kQueued;
  std::vector<std::uint16_t> lost;
};

// The alternatives in the order a round carries them (core::Round): a mission before its
// object's moves, those before freeze / continue, signals and phases last.
using MissionMessage =
    std::variant<MissionSpec, ObjectUpdate, ObjectDelete, Freeze, Continue, Signal, PhaseStatus>;

// std::visit with one lambda per alternative.
template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

// The message's kind, for log lines ("order", "object update", ...).
const char* KindName(const MissionMessage& message);
// The mission a message is about (0 for freeze / continue, which name robots).
std::uint16_t MissionIdOf(const MissionMessage& message);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_MISSION_MESSAGE_H_
