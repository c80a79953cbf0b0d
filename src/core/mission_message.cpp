#include "swarm_transport/core/mission_message.h"

namespace swarm_transport {
namespace core {
const char* KindName(const MissionMessage& message) {
  static const char* const kNames[] = {"order",    "object update", "object delete", "freeze",
                                       "continue", "signal",        "status"};
  static_assert(sizeof(kNames) / sizeof(kNames[0]) == std::variant_size_v<MissionMessage>);
  return kNames[message.index()];
}

std::uint16_t MissionIdOf(const MissionMessage& message) {
  return std::visit(Overloaded{[](const MissionSpec& m) { return m.id; },
                               [](const Freeze&) { return std::uint16_t{0}; },
                               [](const Continue&) { return std::uint16_t{0}; },
                               [](const auto& m) { return m.mission_id; }},
                    message);
}

}  // namespace core
}  // namespace swarm_transport
