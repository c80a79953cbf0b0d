// The lock-step relay of mission messages and the relayed positions: what the simulator (and
// the batch engine, which plays it) hands the robots inside their rounds besides the radio's
// positions. Messages only: no node handle, no clock, so it is tested without a master.
#ifndef SWARM_TRANSPORT_ROS_MISSION_RELAY_H_
#define SWARM_TRANSPORT_ROS_MISSION_RELAY_H_

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/Delete_Object.h"
#include "swarm_transport/Flocking_Tuning.h"
#include "swarm_transport/Mission_Event.h"
#include "swarm_transport/Mission_Status.h"
#include "swarm_transport/Neighbors.h"
#include "swarm_transport/New_Mission.h"
#include "swarm_transport/Robot_Continue.h"
#include "swarm_transport/Robot_Freeze.h"
#include "swarm_transport/Robot_Position.h"
#include "swarm_transport/Tick_Answer.h"
#include "swarm_transport/Update_Object.h"
#include "swarm_transport/core/swarm_config.h"
#include "swarm_transport/sim/radio.h"

namespace swarm_transport {

// The relay's sender of robot `id`'s answer, "robot_%05u": after every node name (they start
// with '/'), in ascending robot id.
std::string AnswerSender(std::uint16_t id);

// Lock-step: the mission messages received during tick k, relayed in every robot's round of
// tick k + 1 (robots in lock-step subscribe to no mission topic). Each list is ordered by sender
// (stable: per sender and topic, arrival is FIFO), so a round does not depend on which
// process's message arrived first. Senders are publishing nodes ("/mission_dispatcher") or
// robots' answers (AnswerSender). Orders wait for their start tick.
class MissionRelay {
 public:
  // An order, held until the tick it is stamped with (New_Mission::start_tick).
  void AddOrder(const std::string& sender, const New_Mission& order);
  void Add(const std::string& sender, const Update_Object& msg);
  void Add(const std::string& sender, const Delete_Object& msg);
  void Add(const std::string& sender, const Robot_Freeze& msg) { Push(sender, msg, &freezes_); }
  void Add(const std::string& sender, const Robot_Continue& msg) { Push(sender, msg, &continues_); }
  void Add(const std::string& sender, const Mission_Event& msg) { Push(sender, msg, &events_); }
  void Add(const std::string& sender, const Mission_Status& msg);
  // What robot `id` said in its answer (not its progress, which only observers get).
  void AddAnswer(std::uint16_t id, const Tick_Answer& answer);

  // The held orders due by `tick` join this tick's relay, in arrival order; returned so that the
  // caller can enter them in its books.
  std::vector<New_Mission> ReleaseOrders(std::uint64_t tick);
  // This tick's messages into a robot's round (sorted once per tick).
  void Fill(Neighbors* round);
  // For a robot whose process connected since the last round (after Fill): the orders released
  // in earlier rounds whose missions have not ended (no DONE, ABORTED or REJECTED, no
  // Delete_Object relayed since), their objects where last reported, each with its latest
  // phase, unless the round carries them already. A latched topic would give a late subscriber
  // its orders too; without them the robot would never learn of a mission sent before it
  // connected (one naming it would stay queued for good).
  void FillStanding(Neighbors* round) const;
  std::size_t standing_orders() const { return standing_.size(); }
  // After the round went out: the lists start empty for the next tick (held orders stay).
  void Clear();
  std::size_t held_orders() const { return pending_.size(); }

 private:
  template <typename M>
  using List = std::vector<std::pair<std::string, M>>;
  template <typename M>
  void Push(const std::string& sender, const M& msg, List<M>* list) {
    list->emplace_back(sender, msg);
    sorted_ = false;
  }
  void Sort();

  // A released order whose mission has not ended, as it stands now.
  struct Standing {
    New_Mission order;
    std::optional<Mission_Status> phase;  // its latest phase status
  };

  // It has a phase status past QUEUED (its first leader started it).
  static bool Started(const Standing& standing);

  List<New_Mission> pending_;                   // received, waiting for their start tick
  std::map<std::uint16_t, Standing> standing_;  // by mission id (unique among live missions)
  List<New_Mission> missions_;
  List<Update_Object> updates_;
  List<Delete_Object> deletes_;
  List<Robot_Freeze> freezes_;
  List<Robot_Continue> continues_;
  List<Mission_Event> events_;
  List<Mission_Status> statuses_;
  bool sorted_ = true;
  Neighbors round_;  // the sorted lists, copied into every round
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
  std::optional<Flocking_Tuning> BeginRound(std::uint64_t tick);
  // The current tuning into a robot's round (nothing before the first change).
  void Fill(Neighbors* round) const;
  // The newest accepted values (pending or current), and the configuration with them.
  core::FlockingTuning newest() const { return core::FlockingTuning::Of(config_.flocking); }
  const core::SwarmConfig& config() const { return config_; }
  std::uint32_t generation() const { return current_ ? current_->generation : 0; }

 private:
  core::SwarmConfig config_;  // with the newest accepted tuning
  bool pending_ = false;
  std::optional<Flocking_Tuning> current_;
};

// The positions relayed besides the world's robots (announced on /flock/position): leaders'
// virtual copies (type 1) and statists (type 2), the latest per (robot id, sub id).
class RelayedPositions {
 public:
  // Empty when taken, else why not (a non-finite value, an unknown type; a physical robot's
  // own position is ignored: the world's truth is relayed). Angles are kept in [0, 360) degrees.
  std::string Take(const Robot_Position& msg);
  bool Ignored(const Robot_Position& msg) const {
    return msg.type == Robot_Position::TYPE_PHYSICAL;
  }
  // False when there was none.
  bool Erase(std::uint16_t robot_id, std::uint8_t sub_id);
  // A killed robot's virtual copies die with it.
  void EraseCopiesOf(std::uint16_t robot_id);
  // For the radio: every relayed position, in key order.
  std::vector<sim::RadioExtra> Extras() const;
  // The relayed positions of the current round: a virtual copy whose owner stands at index
  // `owner[k]` of `truth` (the radio's extra_owner) is relayed at its owner's true pose.
  std::vector<Robot_Position> AtOwners(const std::vector<long>& owner,
                                       const std::vector<Robot_Position>& truth) const;
  std::size_t size() const { return positions_.size(); }

 private:
  std::map<std::pair<std::uint16_t, std::uint8_t>, Robot_Position> positions_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_MISSION_RELAY_H_
