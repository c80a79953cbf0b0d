// The lock-step tick [SPEC 7], once: what the world, the radio and the relay make of a tick -
// every robot's round, and what the robots' answers do to the next round and to the
// simulator's books. The ROS simulator drives it between its waits (LockstepSession: who is
// live, when a tick is complete) and the batch runs (ros/engine/batch_run.h) drive it with their
// robots' sessions in the same process; neither has a tick of its own. Rounds and answers are
// core types (core/round.h): no ROS, no clock, no waiting.
//
// A tick:
//   ReleaseOrders   the orders due enter the relay and the books
//   BeginRound      the radio samples the world (the relayed positions, the quiet robots)
//   Round           per robot that gets a round, in world order: radio + relay
//   EndRound        the relay's lists start empty for what the answers say
//   TakeAnswers     the tick's answers, by robot id: into the next relay and the books
//   core::CommandOf an answer's command (a non-finite one stands)
#ifndef SWARM_TRANSPORT_SIM_LOCKSTEP_ENGINE_H_
#define SWARM_TRANSPORT_SIM_LOCKSTEP_ENGINE_H_

#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/sim/live_mission.h"
#include "swarm_transport/sim/mission_relay.h"
#include "swarm_transport/sim/radio.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace sim {

class LockstepEngine {
 public:
  // `world`, `radio` and `missions` (the simulator's books: the mission channel and the
  // markers) must outlive the engine.
  LockstepEngine(const World2D* world, Radio* radio, LiveMissions* missions);

  // Where the dispatcher's orders and messages, the robots' topics and a scenario's events
  // enter the relay (each with its sender).
  MissionRelay& relay() { return relay_; }
  const LiveMissions& missions() const { return *missions_; }

  // Tick `tick` begins: the held orders due by then enter this tick's relay and the books.
  // Returns those the books did not enter, with why (an order the robots refuse too).
  std::vector<std::pair<core::MissionSpec, std::string>> ReleaseOrders(std::uint64_t tick);
  // The radio samples the world for round `tick` at simulated time `sim_time`: `relayed`
  // (may be null) are the positions relayed besides the world's robots (virtual copies,
  // statists) and the copies robots announced on their positions in real time, `quiet` the
  // robots nobody hears this round. A robot's position carries the virtual copies its latest
  // answer announced (Position::copies).
  void BeginRound(std::uint64_t tick, double sim_time, const RelayedPositions* relayed,
                  const std::set<std::uint16_t>& quiet);
  // The round of the robot at world index `index` (call in ascending index; the radio draws
  // its losses in call order): its pose, what it hears, the relayed mission messages, and, for
  // a robot whose process has just connected, the orders of the missions that have not ended
  // (MissionRelay::FillStanding; returns how many it added).
  std::size_t Round(std::size_t index, bool connected, core::Round* out);
  double sim_time() const { return sim_time_; }
  // The physical robots' true poses of the round, in world order (/flock/world_poses).
  const std::vector<core::Position>& truth() const { return truth_; }
  std::vector<core::Position> TakeTruth() { return std::move(truth_); }
  // Every round went out: the relay's lists start empty (held orders stay).
  void EndRound() { relay_.Clear(); }

  // A tick's answers (a late one before its robot's current one): sorted by robot id (stable),
  // each into the next tick's relay, the books and its robot's announced copies, then handed to
  // `observe` (the simulator's topics for observers; the batch engine's dispatcher and
  // recorder). Empties `answers`.
  using Answers = std::vector<std::pair<std::uint16_t, core::Answer>>;
  void TakeAnswers(Answers* answers,
                   const std::function<void(std::uint16_t, const core::Answer&)>& observe);

 private:
  // Each robot's position in truth_ carries the copies `copies` names for it.
  void StampCopies(const std::map<std::uint16_t, std::uint8_t>& copies);

  const World2D* world_;
  Radio* radio_;
  LiveMissions* missions_;
  MissionRelay relay_;
  std::uint64_t tick_ = 0;
  double sim_time_ = 0.0;
  std::vector<core::Position> truth_;
  std::vector<core::Position> relayed_;
  std::map<std::uint16_t, std::uint8_t> copies_;  // by robot: the copies its answer announced
  RadioRound heard_;
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_LOCKSTEP_ENGINE_H_
