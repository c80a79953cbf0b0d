// The lock-step relay of mission messages and the relayed positions: what the simulator (and
// the batch runs, which play it) hands the robots inside their rounds besides the radio's
// positions. Core types only (core/round.h): no ROS, no clock.
#ifndef SWARM_TRANSPORT_SIM_MISSION_RELAY_H_
#define SWARM_TRANSPORT_SIM_MISSION_RELAY_H_

#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "swarm_transport/core/mission.h"
#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/core/swarm_config.h"
#include "swarm_transport/sim/radio.h"

namespace swarm_transport {
namespace sim {

// The relay's sender of robot `id`'s answer, "robot_%05u": after every node name (they start
// with '/'), in ascending robot id.
std::string AnswerSender(std::uint16_t id);

// Lock-step: the mission messages received during tick k, relayed in every robot's round of
// tick k + 1 (robots in lock-step subscribe to no mission topic). Each kind is ordered by sender
// (stable: per sender and kind, arrival is FIFO), so a round does not depend on which
// process's message arrived first. Senders are publishing nodes ("/mission_dispatcher") or
// robots' answers (AnswerSender). Orders wait for their start tick.
class MissionRelay {
 public:
  // An order, held until tick `start_tick`.
  void AddOrder(const std::string& sender, const core::MissionSpec& order,
                std::uint64_t start_tick);
  // Any other mission message (an order given here is relayed at once).
  void Add(const std::string& sender, const core::MissionMessage& message);
  // What robot `id` said in its answer (not its progress, which only observers get).
  void AddAnswer(std::uint16_t id, const core::Answer& answer);

  // The held orders due by `tick` join this tick's relay, in arrival order; returned so that the
  // caller can enter them in its books.
  std::vector<core::MissionSpec> ReleaseOrders(std::uint64_t tick);
  // This tick's messages into a robot's round (sorted once per tick).
  void Fill(core::Round* round);
  // For a robot whose process connected since the last round (after Fill): the orders released
  // in earlier rounds whose missions have not ended (no DONE, ABORTED or REJECTED, no object
  // delete relayed since), their objects where last reported, each with its latest phase,
  // unless the round carries them already. A latched topic would give a late subscriber its
  // orders too; without them the robot would never learn of a mission sent before it
  // connected (one naming it would stay queued for good). Returns how many orders it added.
  std::size_t FillStanding(core::Round* round) const;
  std::size_t standing_orders() const { return standing_.size(); }
  // After the round went out: the lists start empty for the next tick (held orders stay).
  void Clear();
  std::size_t held_orders() const { return pending_.size(); }

 private:
  static constexpr std::size_t kKinds = std::variant_size_v<core::MissionMessage>;
  using List = std::vector<std::pair<std::string, core::MissionMessage>>;
  void Push(const std::string& sender, const core::MissionMessage& message);
  void Sort();

  // A released order whose mission has not ended, as it stands now.
  struct Standing {
    core::MissionSpec order;
    std::optional<core::MissionPhase> phase;  // its latest phase status
    std::set<std::uint16_t> lost;             // the robots its statuses named lost so far
  };
  // It has a phase status past QUEUED (its first leader started it).
  static bool Started(const Standing& standing);
  void Note(const core::ObjectUpdate& m);
  void Note(const core::ObjectDelete& m);
  void Note(const core::PhaseStatus& m);
  template <typename M>
  void Note(const M&) {}

  struct Held {
    std::string sender;
    core::MissionSpec order;
    std::uint64_t start_tick = 0;
  };
  std::vector<Held> pending_;                   // received, waiting for their start tick
  std::map<std::uint16_t, Standing> standing_;  // by mission id (unique among live missions)
  std::array<List, kKinds> lists_;              // by kind (the variant's index)
  bool sorted_ = true;
  std::vector<core::MissionMessage> round_;  // the sorted lists, copied into every round
};

// Live tuning of the flocking parameters (issue 13): a change accepted between two rounds goes
// out with the next round, inside every robot's round from then on (a robot that joins later
// gets it too), so that in lock-step every robot uses it from the same tick. Validated with the
// robots' own check against the whole configuration.
class TuningRelay {
 public:
  explicit TuningRelay(const core::SwarmConfig& config);
  // Empty when accepted (it goes out with the next round; a later proposal before that round
  // replaces it; the values already in use change nothing), else why not: nothing changed.
  std::string Propose(const core::FlockingTuning& tuning);
  // Round `tick` begins: an accepted change becomes current and is returned (once).
  std::optional<core::TuningGeneration> BeginRound(std::uint64_t tick);
  // The current tuning into a robot's round (nothing before the first change).
  void Fill(core::Round* round) const { round->tuning = current_; }
  // The newest accepted values (pending or current), and the configuration with them.
  core::FlockingTuning newest() const { return core::FlockingTuning::Of(config_.flocking); }
  const core::SwarmConfig& config() const { return config_; }
  std::uint32_t generation() const { return current_ ? current_->generation : 0; }

 private:
  core::SwarmConfig config_;  // with the newest accepted tuning
  bool pending_ = false;
  std::optional<core::TuningGeneration> current_;
};

// The positions relayed besides the world's robots (announced by their robots or placed by the
// dispatcher and scenarios): leaders' virtual copies and statists, the latest per (robot id,
// sub id).
class RelayedPositions {
 public:
  // Empty when taken, else why not (a non-finite value, an unknown type; of a physical robot's
  // own position only the copies it announces are kept - the world's truth is relayed).
  // Angles are kept in [0, 360) degrees.
  std::string Take(const core::Position& position);
  bool Ignored(const core::Position& p) const { return p.type == core::Position::kPhysical; }
  // False when there was none.
  bool Erase(std::uint16_t robot_id, std::uint8_t sub_id);
  // A killed robot's virtual copies die with it (those it announced on its position too).
  void EraseCopiesOf(std::uint16_t robot_id);
  // By robot: the virtual copies it announced on its own latest position (none: not listed).
  const std::map<std::uint16_t, std::uint8_t>& copies() const { return copies_; }
  // For the radio: every relayed position, in key order.
  std::vector<RadioExtra> Extras() const;
  // The relayed positions of the current round: a virtual copy whose owner stands at index
  // `owner[k]` of `truth` (the radio's extra_owner) is relayed at its owner's true pose.
  std::vector<core::Position> AtOwners(const std::vector<long>& owner,
                                       const std::vector<core::Position>& truth) const;
  std::size_t size() const { return positions_.size(); }

 private:
  std::map<std::pair<std::uint16_t, std::uint8_t>, core::Position> positions_;
  std::map<std::uint16_t, std::uint8_t> copies_;
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_MISSION_RELAY_H_
