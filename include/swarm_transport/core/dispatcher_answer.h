// Lock-step: the mission dispatcher's answer to the simulator's barrier [SPEC 7, 9.4], one typed
// message (swarm_transport/Dispatcher_Answer; the batch runs take it as it is). The dispatcher
// answers at every positions it takes and after every status it takes; an answer says what it
// has taken and what it sent, and which ticks wait for its next answers. The barrier waits for
// exactly that (sim/lockstep_barrier.h) and knows nothing of why the dispatcher sent it.
#ifndef SWARM_TRANSPORT_CORE_DISPATCHER_ANSWER_H_
#define SWARM_TRANSPORT_CORE_DISPATCHER_ANSWER_H_

#include <cstdint>
#include <optional>
#include <tuple>
#include <utility>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_message.h"

namespace swarm_transport {
namespace core {

// A mission's status as its first leader reported it in tick `tick`.
struct StatusKey {
  std::uint16_t mission_id = 0;
  MissionPhase phase = MissionPhase::kQueued;
  std::uint64_t tick = 0;
  bool operator<(const StatusKey& o) const {
    return std::tie(mission_id, phase, tick) < std::tie(o.mission_id, o.phase, o.tick);
  }
  bool operator==(const StatusKey& o) const {
    return mission_id == o.mission_id && phase == o.phase && tick == o.tick;
  }
};

// A recruiting mission's statist as the simulator must place it (SPEC 9.4, lock-step).
struct RecruitStatist {
  std::uint16_t mission_id = 0;
  std::uint16_t statist_id = 0;
  Vec2 at;                      // its object's centre
  int copies = 1;               // stacked as sub_ids 0 .. copies - 1
  std::uint64_t from_tick = 0;  // it stands from this tick
};

struct DispatcherAnswer {
  bool has_positions = false;      // it has taken positions: checked_tick counts
  std::uint64_t checked_tick = 0;  // the latest tick whose positions it has taken
  std::optional<StatusKey>
      status;  // the status this answer follows (taken, whatever it made of it)
  // What it sent since its last answer: orders (id, start tick), each waited for from its start
  // tick on, and LOADED / UNLOADED, waited for by the next tick.
  std::vector<std::pair<std::uint16_t, std::uint64_t>> orders;
  std::vector<Signal> events;
  // Every tick t >= hold_from_tick (0: none) waits for an answer with checked_tick >= t - 1.
  std::uint64_t hold_from_tick = 0;
  std::vector<RecruitStatist> recruiting;  // every mission recruiting now, with its statist
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_DISPATCHER_ANSWER_H_
