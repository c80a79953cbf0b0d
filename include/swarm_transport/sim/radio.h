// The radio [SPEC 7]: who hears whom in one round. Pure (no ROS, no clock): the simulator's
// adapter turns a round into a Neighbors message. Positions are the world's true poses.
#ifndef SWARM_TRANSPORT_SIM_RADIO_H_
#define SWARM_TRANSPORT_SIM_RADIO_H_

#include <cstddef>
#include <cstdint>
#include <set>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/random.h"
#include "swarm_transport/sim/live_mission.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace sim {

// The stream of the seed's generator that draws a run's radio losses ("radio"; robots use their
// id, < 65536, as stream).
constexpr std::uint64_t kRadioLossStream = 0x726164696fULL;

struct RadioParams {
  double range_m = 1.0;  // a robot hears the robots whose centre is within this of its own
  // Hops of a chain: 1 = only the robots in range; k > 1 = also what they heard in range,
  // passed on hop by hop up to k hops (SPEC 7, the chain neighbourhood).
  int hops = 1;
  double loss = 0.0;  // drop probability per delivered position, [0, 1]
};

// A position relayed besides the physical robots, announced on /flock/position.
struct RadioExtra {
  bool virtual_copy = false;  // a leader's virtual copy (type 1); else a statist (type 2)
  std::uint16_t owner = 0;    // the robot it belongs to (copies)
  core::Vec2 position;        // where it was announced
};

// What one robot hears in a round: indices into the round's robots (the world's, ascending
// id) or extras. A robot is listed at most once, its own index never.
struct RadioRound {
  std::vector<std::size_t> in_range;  // physical robots within range, ascending
  std::vector<std::size_t> chain;     // beyond range, heard hop by hop (hop order, then id)
  std::vector<std::size_t> extras;    // copies of others in range, and every statist
  std::vector<std::size_t> peers;     // members of its missions it did not hear otherwise
};

class Radio {
 public:
  // `loss_rng` draws the losses (used only when params.loss > 0); it must outlive the radio.
  Radio(const RadioParams& params, core::Rng* loss_rng);

  // Starts a round over `world`'s current poses. A virtual copy whose owner is in the world
  // stands at its owner's true pose (what a neighbour hears does not depend on when the copy's
  // message arrived); other extras where they were announced.
  // `quiet`: robots whose radio is silent this round (dead or hung: they do not answer their
  // ticks) - nobody hears them, in range, hop by hop or over the mission channel; they still
  // hear the others.
  void Begin(const World2D& world, std::vector<RadioExtra> extras, const LiveMissions& missions,
             const std::set<std::uint16_t>& quiet = {});
  // The round of the robot at index `i` of the world's robots. Losses are drawn in call order:
  // call in ascending `i` for a reproducible round.
  void Hear(std::size_t i, RadioRound* out);

  // Of the current round: ids and extras' effective positions, and for each extra the index
  // of the robot it stands on (-1: none).
  const std::vector<std::uint16_t>& ids() const { return ids_; }
  const std::vector<long>& extra_owner() const { return extra_owner_; }
  // A new range from the next Begin() on (a live tuning of the local range, issue 13).
  void set_range_m(double range_m) { params_.range_m = range_m; }
  // A new loss probability from the next Hear() on (a live change, dynamic_reconfigure).
  void set_loss(double loss) { params_.loss = loss; }

 private:
  long IndexOf(std::uint16_t id) const;
  bool Lost();

  RadioParams params_;
  core::Rng* loss_rng_;
  std::vector<std::uint16_t> ids_;
  std::vector<core::Vec2> positions_;
  World2D::NeighbourTable table_;  // in range, by index; quiet robots left out
  std::vector<RadioExtra> extras_;
  std::vector<long> extra_owner_;
  std::vector<std::vector<std::size_t>> missions_of_;  // per robot: its missions' member lists
  std::vector<std::vector<std::uint16_t>> member_lists_;
  std::vector<char> heard_;
  std::vector<char> quiet_;  // per robot index
  std::vector<std::size_t> touched_;
  std::vector<std::size_t> ring_;
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_RADIO_H_
