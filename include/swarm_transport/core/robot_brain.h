// One robot's whole behaviour, pure: the mission messages it takes in, the freeze state, its
// random generator and leader memory, and one tick from a perception to a velocity command, the
// mission messages a first leader must send and a typed state. The robot node only moves bytes
// between ROS and this class [issue 10].
#ifndef SWARM_TRANSPORT_CORE_ROBOT_BRAIN_H_
#define SWARM_TRANSPORT_CORE_ROBOT_BRAIN_H_

#include <cstdint>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/leader.h"
#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_agent.h"
#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/core/random.h"
#include "swarm_transport/core/swarm_config.h"
#include "swarm_transport/core/transport.h"

namespace swarm_transport {
namespace core {

// An order the brain took.
struct MissionTaken {
  bool first_leader = false;  // it runs the mission's phases and publishes its messages
  // Its first leader's first status (QUEUED, with the object and the robots assigned).
  StatusReport queued;
};

// The outcome of one tick.
struct BrainTick {
  Velocity command;      // zero while frozen (a leader under its object may turn in place)
  MoveDecision move;     // what its behaviour decided (also while frozen)
  MissionOutbox outbox;  // what a first leader must send before the command
  // A leader-only mission's leader arrived this tick (its outbox holds the DONE).
  bool arrived = false;
  // Virtual copies it announces with its position (SPEC 9.2): leader_virtual_copies - 1 while
  // it leads a leader-only mission, else 0.
  std::uint8_t copies = 0;
};

class RobotBrain {
 public:
  // `config` must be valid (SwarmConfig::Validate).
  RobotBrain(std::uint16_t id, const SwarmConfig& config);

  // The inbox: one mission message, whatever carried it. Empty when taken, else the reason it
  // was not (its state is then unchanged). Freeze / continue apply to robots in [from, to), an
  // empty or inverted range is rejected; a phase beyond kRejected is ignored. `known_robots`:
  // the physical robots the swarm has now (a mission must name only those); `taken` (may be
  // null) is filled for a mission taken.
  std::string Take(const MissionMessage& message, const std::set<std::uint16_t>& known_robots = {},
                   MissionTaken* taken = nullptr);

  // New flocking parameters (dynamic_reconfigure, issue 13), used from the next Tick on: empty
  // when taken, else why not (nothing changed).
  std::string OnTuning(const FlockingTuning& tuning);

  // One tick on `in` (its own pose, what it hears; zones and group are the brain's to set).
  // `publish`: whether its mission messages can go out now (a first leader whose subscribers
  // are not connected yet holds its phase machine and sends nothing).
  BrainTick Tick(Perception in, std::uint64_t tick, bool publish);

  std::uint16_t id() const { return id_; }
  bool frozen() const { return frozen_; }
  // Who may order it: the dispatcher (its admitted orders) or anyone (core::MayOrder).
  Admission admission() const { return params_.admission; }
  const MissionAgent& missions() const { return agent_; }
  // Whether its peers hear it while it misses ticks (MissionAgentParams::heard_while_hung).
  void set_heard_while_hung(bool heard) { agent_.set_heard_while_hung(heard); }
  const MissionPlan& last_plan() const { return last_plan_; }
  const MoveDecision& last_move() const { return last_move_; }
  std::size_t last_heard() const { return last_heard_; }
  // Its own pose as its last tick knew it (what it planned from; the world may differ).
  const Pose2& last_self() const { return last_self_; }
  // Its balloon's radius (m): the robot's radius unless it is in balloon standby.
  double balloon_radius_m() const { return balloon_radius_m_; }
  // The flocking parameters it uses now (its configuration's until a tuning came).
  FlockingTuning tuning() const { return FlockingTuning::Of(params_.flocking); }

 private:
  // The inbox by kind (what Take calls).
  std::string OnFreeze(std::uint16_t from, std::uint16_t to);
  std::string OnContinue(std::uint16_t from, std::uint16_t to);
  // `known_robots`: the physical robots the swarm has now (a mission must name only those).
  std::string OnNewMission(const MissionSpec& mission, const std::set<std::uint16_t>& known_robots,
                           MissionTaken* taken);
  std::string OnObjectUpdate(std::uint16_t mission_id, Vec2 centre);
  std::string OnObjectDelete(std::uint16_t mission_id);
  std::string OnEvent(std::uint16_t mission_id, MissionEventKind event,
                      std::uint64_t not_before_tick);
  // A status published by a mission's first leader (how members learn its phase and who is
  // lost, MissionAgent::OnStatus); a value beyond kRejected is ignored.
  void OnStatus(const PhaseStatus& status);
  bool InRange(std::uint16_t from, std::uint16_t to) const { return from <= id_ && id_ < to; }

  std::uint16_t id_;
  SwarmConfig params_;
  Rng rng_;
  MissionAgent agent_;
  LeaderMemory leader_memory_;
  std::optional<std::uint16_t> leader_memory_mission_;
  bool frozen_ = false;
  MissionPlan last_plan_;
  MoveDecision last_move_;
  std::size_t last_heard_ = 0;
  Pose2 last_self_;
  // Balloon standby (SPEC 9.5): its balloon's radius, reset whenever it is not in standby.
  double balloon_radius_m_ = 0.0;
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_ROBOT_BRAIN_H_
