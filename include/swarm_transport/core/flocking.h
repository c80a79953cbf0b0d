// One robot's flocking step [SPEC 4, T5.2]: alignment, free will, cohesion, flight from danger
// / into safety, collision avoidance. Pure: everything it needs comes in as arguments.
#ifndef SWARM_TRANSPORT_CORE_FLOCKING_H_
#define SWARM_TRANSPORT_CORE_FLOCKING_H_

#include <cstdint>
#include <string>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/random.h"

namespace swarm_transport {
namespace core {

// Which robots form a robot's swarm [SPEC 4, THESIS_CODE 1]: the chain (the connected component
// of robots linked hop by hop within local range, itself included), or the disc (only robots
// within local range of itself).
enum class Neighbourhood { kChain, kDisc };
// "chain" / "disc"; false for anything else.
bool ParseNeighbourhood(const std::string& name, Neighbourhood* out);
const char* NeighbourhoodName(Neighbourhood n);

// The behaviour parameters of a robot, with units in the names.
struct FlockingParams {
  double local_range_m = 1.0;       // neighbourhood radius
  double speed_m_per_tick = 0.1;    // distance driven per tick
  double free_will_deg = 90.0;      // width of the uniform heading noise, [0, 360]
  double cohesion = 0.0;            // fraction of the turn towards the centroid, [-1, 1]
  double robot_radius_m = 0.05;     // disc radius
  double collision_margin = 0.1;    // keep >= 2 * radius * (1 + margin) between centres
  double world_size_m = 11.088889;  // square arena [0, world_size]^2
  double speed_reduction = 0.5;     // factor applied to the speed on each retry, (0, 1)
  int speed_retries = 2;            // retries at lower speed after a failed +-180 search
  bool check_path = true;           // also reject moves whose path crosses a robot's disc
  double zone_margin_m = 0.02;      // flight aims this far inside the allowed region
  Neighbourhood neighbourhood = Neighbourhood::kChain;  // whom alignment and cohesion run over

  // Empty when valid, else one sentence naming the first bad field and the accepted range.
  std::string Validate() const;
  // Centre-to-centre distance two robots must keep.
  double MinSeparation() const { return 2.0 * robot_radius_m * (1.0 + collision_margin); }
};

// Another robot as this robot perceives it.
struct Neighbour {
  std::uint16_t id = 0;
  std::uint8_t sub_id = 0;
  std::uint8_t type = 0;  // 0 physical, 1 virtual copy, 2 statist (core::Position::Type)
  // Virtual copies its robot announced with this position (a physical robot's only, SPEC 9.2):
  // NeighbourhoodOf lists them as neighbours of type 1 wherever it lists the robot.
  std::uint8_t copies = 0;
  Vec2 position;
  Angle heading;
};

// The candidates of a robot's swarm: all physical robots but `ids` (idle: the members of
// transport missions it is not part of), or only `ids` (on a transport mission: its group)
// [THESIS_CODE 1]. Statists always count; a virtual copy counts when its robot does.
struct FlockGroup {
  bool only = false;
  std::vector<std::uint16_t> ids;  // ascending
  bool Admits(std::uint16_t id) const;
};

// What a robot knows at the start of its tick.
struct Perception {
  std::uint16_t self_id = 0;
  Pose2 self;
  // Every other robot heard this tick (the step filters by range; statists always count).
  std::vector<Neighbour> others;
  // Zones that apply to this robot (danger and safety).
  std::vector<Zone> zones;
  // Who may be in its swarm (collisions count every robot in `others` regardless).
  FlockGroup group;
};

// Why the executed move differs from the desired heading.
enum class MoveOutcome { kStraight, kSwerved, kSlowed, kStand };

// The result of a tick's computation.
struct MoveDecision {
  Angle desired_heading;    // after alignment, free will, cohesion / flight
  Angle heading;            // heading of the executed move
  double distance_m = 0.0;  // distance of the executed move (0 = stand)
  MoveOutcome outcome = MoveOutcome::kStand;
  bool fleeing = false;         // step 4 applied
  int neighbours_in_range = 0;  // its neighbourhood's robots and statists, itself included
};

// A move that stays where it is: it wants `desired` and ends facing `heading`.
MoveDecision StandStill(Angle desired, Angle heading);

// The robots (and copies / statists) alignment and cohesion run over, itself first: the
// candidates `in.group` admits, linked to itself within local range - directly (disc) or hop
// by hop (chain) - and every statist regardless of range.
std::vector<Neighbour> NeighbourhoodOf(const Perception& in, const FlockingParams& p);
// Its robots and statists: virtual copies weigh in alignment but are nobody to count.
int NeighbourhoodSize(const std::vector<Neighbour>& neighbourhood);

// Steps 1-4: the heading the robot wants. Draws exactly one free-will sample from `rng` every
// call (also when fleeing) so the random sequence never depends on the branch taken.
// `neighbourhood_size` (optional) receives NeighbourhoodSize of NeighbourhoodOf(in, p),
// computed once.
Angle DesiredHeading(const Perception& in, const FlockingParams& p, Rng& rng, bool* fleeing,
                     int* neighbourhood_size = nullptr);

// Stacking by the hearer (a carrying robot's transport_leader_weight; a leader-only mission's
// leader announces its copies itself, Neighbour::copies): `in` with weight - 1 virtual copies (type
// 1, sub_id 1..) of every physical robot heard whose id is in `leaders` (ascending), for an
// alignment that weighs each of them `weight` times; collisions and the neighbourhood count take
// `in` itself.
Perception StackLeaders(const Perception& in, const std::vector<std::uint16_t>& leaders,
                        int weight);

// True when a move from `self` turning to `heading` and driving `distance_m` within
// `duration_s` is valid: the destination keeps MinSeparation() to every other physical robot,
// lies inside the arena by one radius, is not forbidden by a zone (a robot already in a
// forbidden place may move when it gets no deeper in), and (check_path) the path crosses no
// other robot's disc.
bool IsMoveValid(const Perception& in, const FlockingParams& p, Angle heading, double distance_m,
                 double duration_s);

// Step 5 for a normal robot: desired heading, then +1, -1, +2, -2, ... +-180 degrees; then
// again with speed * speed_reduction (speed_retries times); else stand.
MoveDecision AvoidCollisions(const Perception& in, const FlockingParams& p, Angle desired,
                             double duration_s);

// A whole tick of a passive robot (steps 1-5).
MoveDecision FlockingStep(const Perception& in, const FlockingParams& p, Rng& rng,
                          double duration_s);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_FLOCKING_H_
