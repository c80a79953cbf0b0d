#include "swarm_transport/core/mission_message.h"

namespace swarm_transport {
namespace core {
namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

}  // namespace

const char* KindName(const MissionMessage& message) {
  static const char* const kNames[] = {"New_Mission",   "Update_Object",  "Delete_Object",
                                       "Robot_Freeze",  "Robot_Continue", "Mission_Event",
                                       "Mission_Status"};
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
