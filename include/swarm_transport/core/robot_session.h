// One robot between its messages, without a transport: its brain, the status sequence of the
// missions it leads and its live tuning - a round (or one mission message) in, an answer out
// (core/round.h). Every deployment runs a robot through this class: a robot process and a
// host's robots (RobotNode, which only converts and moves messages between a transport and the
// session) and the batch runs (the lock-step engine hands them their rounds as they are). No
// transport, no clock, no log: what a transport must say about a message it is told
// (Taken::say).
#ifndef SWARM_TRANSPORT_CORE_ROBOT_SESSION_H_
#define SWARM_TRANSPORT_CORE_ROBOT_SESSION_H_

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/core/robot_brain.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/core/swarm_config.h"

namespace swarm_transport {
namespace core {

class RobotSession {
 public:
  // `config` must be valid (SwarmConfig::Validate).
  RobotSession(std::uint16_t id, const SwarmConfig& config);

  // What became of one message, and what its transport should say about it.
  struct Taken {
    enum class Say {
      kNothing,  // taken, or routine (an order for other robots, an update of a mission it
                 // does not hold)
      kDebug,    // not for it (an order it may not take from that sender yet, a signal
                 // for a mission it does not hold: the dispatcher re-sends them)
      kWarn,     // bad input: worth a (throttled) warning
    };
    Say say = Say::kNothing;
    std::string kind;  // the message's kind (KindName: "order", ...)
    std::string why;   // empty when taken
    // It took a mission as its first leader (a real-time robot without mission topics yet
    // advertises them now).
    bool first_leader = false;
  };

  // One mission message from `from` (a topic's publisher; the relay for a lock-step round),
  // checked against who may send it (core::MayOrder, core::MayReport). `known_robots`: the
  // physical robots the swarm has now.
  Taken Take(const MissionMessage& message, const Sender& from,
             const std::set<std::uint16_t>& known_robots);
  // A lock-step round's relayed mission messages, in the round's order (from the relay);
  // what it refused is appended to `refused` (may be null).
  void TakeRelayed(const Round& round, const std::set<std::uint16_t>& known_robots,
                   std::vector<Taken>* refused);
  // A round's flocking tuning (issue 13): a generation it does not have yet is used from this
  // tick on. Returns a refusal (once per generation), else nothing to say.
  Taken TakeTuning(const std::optional<TuningGeneration>& tuning, std::uint64_t tick);
  Taken TakeTuning(const Round& round) { return TakeTuning(round.tuning, round.tick); }

  // One tick on `in`, the round of tick `tick` at simulated time `sim_time`. `ready`: its
  // mission messages can go out now (a real-time first leader whose subscribers are not
  // connected yet holds its phase machine and says nothing). The answer carries every mission
  // message it says (statuses sequenced: one per phase, the rest progress), with `tick`,
  // `sim_time` and its command.
  struct Step {
    BrainTick brain;
    Answer answer;
  };
  Step Tick(Perception in, std::uint64_t tick, double sim_time, bool ready);

  std::uint16_t id() const { return brain_.id(); }
  const RobotBrain& brain() const { return brain_; }
  // Whether its peers hear it while it misses ticks (MissionAgentParams::heard_while_hung).
  void set_heard_while_hung(bool heard) { brain_.set_heard_while_hung(heard); }
  std::uint32_t tuning_generation() const { return tuning_generation_; }
  std::uint64_t tuning_tick() const { return tuning_tick_; }

 private:
  RobotBrain brain_;
  // The QUEUED of the missions it took as first leader and the phase last reported per mission:
  // every status of a mission comes from its first leader, in order.
  StatusSequencer statuses_;
  std::uint32_t tuning_generation_ = 0;   // the live tuning it took (0: its configuration's)
  std::uint64_t tuning_tick_ = 0;         // ... at the round of this tick
  std::uint32_t refused_generation_ = 0;  // the last one it refused (said once)
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_ROBOT_SESSION_H_
