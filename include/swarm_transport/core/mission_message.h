// One mission message as a robot takes it in, whatever carried it: a lock-step round (the
// relay), a topic (real time), a host's shared subscription or a fuzzer. RobotBrain::Take is
// the one inbox; the ROS side only converts (ros/common/conversions.h). A new kind of mission
// message is a new alternative here, its conversion, and its case in RobotBrain::Take.
#ifndef SWARM_TRANSPORT_CORE_MISSION_MESSAGE_H_
#define SWARM_TRANSPORT_CORE_MISSION_MESSAGE_H_

#include <cstdint>
#include <variant>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/mission.h"

namespace swarm_transport {
namespace core {

// Update_Object: the first leader's (or the dispatcher's) new centre of a mission's object.
struct ObjectUpdate {
  std::uint16_t mission_id = 0;
  Vec2 centre;
};

// Delete_Object: the mission's object is gone.
struct ObjectDelete {
  std::uint16_t mission_id = 0;
};

// Robot_Freeze / Robot_Continue: robots with ids in [from, to) stop driving / drive again.
struct Freeze {
  std::uint16_t from = 0;
  std::uint16_t to = 0;
};
struct Continue {
  std::uint16_t from = 0;
  std::uint16_t to = 0;
};

// Mission_Event: the dispatcher's (or a user's) LOADED / UNLOADED, not applied before a tick.
// `kind` is the message's raw value (the brain rejects anything but kLoaded and kUnloaded).
struct Signal {
  std::uint16_t mission_id = 0;
  MissionEventKind kind = MissionEventKind::kLoaded;
  std::uint64_t not_before_tick = 0;
};

// Mission_Status: a mission's phase as its first leader (or the dispatcher) published it; a
// value beyond kRejected is no phase and ignored.
struct PhaseStatus {
  std::uint16_t mission_id = 0;
  MissionPhase phase = MissionPhase::kQueued;
};

// The alternatives in the order a round carries them (Neighbors.msg): a mission before its
// object's moves, those before freeze / continue, signals and phases last.
using MissionMessage =
    std::variant<MissionSpec, ObjectUpdate, ObjectDelete, Freeze, Continue, Signal, PhaseStatus>;

// The message's ROS type name, for log lines ("New_Mission", "Update_Object", ...).
const char* KindName(const MissionMessage& message);
// The mission a message is about (0 for freeze / continue, which name robots).
std::uint16_t MissionIdOf(const MissionMessage& message);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_MISSION_MESSAGE_H_
