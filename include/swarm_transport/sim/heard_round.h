// What a robot on real hardware hears: the other robots' positions as they announced them on
// /flock/position over the network, put through the simulator's very radio (sim::Radio: range,
// hop relay, loss, the mission channel), so that the network is the radio. It assembles the
// robot's round (core::Round) at each of its ticks, as the simulator's engine does for a
// simulated robot. Pure: no ROS, no clock (times are handed in).
#ifndef SWARM_TRANSPORT_SIM_HEARD_ROUND_H_
#define SWARM_TRANSPORT_SIM_HEARD_ROUND_H_

#include <cstdint>
#include <map>
#include <set>
#include <utility>
#include <vector>

#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/mission_message.h"
#include "swarm_transport/core/random.h"
#include "swarm_transport/core/round.h"
#include "swarm_transport/sim/live_mission.h"
#include "swarm_transport/sim/radio.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace sim {

// The stream of the seed's generator that draws robot `id`'s own radio losses on hardware.
std::uint64_t HeardLossStream(std::uint16_t id);

class HeardRound {
 public:
  // Robot `self` in an arena of `world` (its size and robot radius), hearing through a radio of
  // `radio`; a position older than `heard_timeout_s` is not heard (its robot fell silent).
  HeardRound(std::uint16_t self, const RadioParams& radio, const WorldParams& world,
             double heard_timeout_s, std::uint64_t seed);

  // A position announced by another robot (a robot, a leader's virtual copy or a statist),
  // arrived at `now_s`; the newest of each (robot, sub_id) is kept. Its own and non-finite
  // ones are ignored. True when it names a physical robot never heard before.
  bool Hear(const core::Position& position, double now_s);
  // A mission message the robot takes: an order's robots get the mission channel (each hears
  // the others wherever they are), an object's deletion ends it.
  void Take(const core::MissionMessage& message);
  // A robot a robot list names (/flock/robots, where a node publishes one): it counts as known
  // before it was heard. True when it was not known.
  bool Know(std::uint16_t id) { return known_.insert(id).second; }
  // The robots it ever heard or was told of, itself included (the robot list of a swarm without
  // a simulator: a mission naming another robot is refused).
  const std::set<std::uint16_t>& known() const { return known_; }
  // The members of each live mission it knows (ascending ids), by mission id.
  const LiveMissions& missions() const { return missions_; }
  // A new radio range from the next round on (a live tuning of the local range).
  void set_range_m(double range_m) { radio_.set_range_m(range_m); }

  // Round `tick` at `now_s` with its own pose `self` and last velocity: the positions heard
  // within the timeout, as the radio lets it hear them (range, hop relay, loss, mission peers).
  // For the radio's range test a position outside the arena counts at the nearest point inside
  // it; the round carries every position as announced.
  void Assemble(std::uint64_t tick, double now_s, const core::Pose2& self,
                const core::Velocity& velocity, core::Round* out);
  // Of the robots (physical) in `round` as Assemble gave it at `now_s`: how many there are, and
  // those whose latest position arrived within the last `within_s` (by arrival: a position that
  // waited in a network queue looks as fresh as one sent just now).
  std::pair<std::size_t, std::size_t> Delivered(const core::Round& round, double now_s,
                                                double within_s) const;

 private:
  struct Heard {
    core::Position position;
    double at_s = 0.0;
  };

  std::uint16_t self_;
  WorldParams world_params_;
  double heard_timeout_s_;
  core::Rng loss_rng_;
  Radio radio_;
  std::map<std::pair<std::uint16_t, std::uint8_t>, Heard> heard_;  // by (robot, sub_id)
  std::set<std::uint16_t> known_;
  LiveMissions missions_;
  // A round's scratch.
  std::vector<core::Position> robots_;  // the world's robots in world order (self: unused)
  std::vector<core::Position> extras_;
  RadioRound radio_round_;
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_HEARD_ROUND_H_
