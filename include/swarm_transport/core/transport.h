// How a mission robot moves while it gathers under its object and while it carries it
// [SPEC 6, THESIS_CODE 2-3], in swarm mode (the thesis's evaluated code) and in formation mode
// (the hybrid transport of the thesis's conclusion, SPEC 9.6). Pure.
#ifndef SWARM_TRANSPORT_CORE_TRANSPORT_H_
#define SWARM_TRANSPORT_CORE_TRANSPORT_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "swarm_transport/core/flocking.h"

namespace swarm_transport {
namespace core {

// Gathering: hold (drive for the object's centre; inside, go on straight for it while nothing is
// in the way and stand once something is - the thesis's evaluated code stood the moment it was
// inside, which walls off the rim: a late robot of 24 could not get in) or fill (flee in by the
// shortest way, then flock inside to make room for late-comers: the thesis's text [T5.4]).
enum class GatherMode { kHold, kFill };
bool ParseGatherMode(const std::string& name, GatherMode* out);

// (ext) Where each mission robot goes while gathering [SPEC 9.10, R3]: nearest (no plan: the
// gathering mode, hold or fill, for everyone) or its own slot under the object, slots spread
// over the object (SlotsIn) and given out by the paper's selection matrix, by the least total
// time (Hungarian, "optimal"), by the least last arrival (bottleneck) or by the paper's naive
// baseline, each robot its own nearest slot in time with no exclusion (row_minimum, issue 27:
// several robots may share a slot).
enum class GatherPlanner { kNearest, kSelectionMatrix, kOptimal, kBottleneck, kRowMinimum };
bool ParseGatherPlanner(const std::string& name, GatherPlanner* out);
const char* GatherPlannerName(GatherPlanner planner);

// The order's transport_mode.
enum class TransportMode : std::uint8_t { kSwarm = 0, kFormation = 1 };

// Parameters of carrying; the defaults are the thesis's evaluated code (THESIS_CODE 2).
struct TransportParams {
  GatherMode gathering = GatherMode::kHold;
  // (ext) Slots under the object by a plan, or nearest (none: the default, the thesis's way).
  GatherPlanner gather_planner = GatherPlanner::kNearest;
  // (ext) A planned gathering re-plans every this many ticks (the paper's "every moment t").
  int replan_period_ticks = 10;
  // (ext) The planner's turn rate VA (degrees per tick): a robot here turns at once within its
  // tick, so a turn of up to 180 degrees costs at most one tick.
  double planner_turn_deg_per_tick = 180.0;
  // Leaders' destinations stay inside the object like everyone's (thesis code); false lets a
  // carrying leader head for the target wherever the object is (only robots stop it).
  bool leaders_bound = true;
  double lookahead = 1.5;         // passive: the point lookahead x its step ahead must be inside
  double passive_slowdown = 0.9;  // passive: speed factor after a failed +-180 degree search
  int passive_tries = 40;         // ... this many times at most (thesis: until legal), then stand
  double leader_slowdown = 0.75;  // leader: speed factor after a blocked move
  int leader_tries = 10;          // ... this many times at most, then it turns and holds
  // (ext) A leader up to this far outside its object keeps its course (moving no farther out,
  // else facing it) instead of driving for the centre: its heading keeps voting for the course
  // in its swarm's alignment (0: the thesis's code, every robot outside drives for the centre).
  // Default 0: with leaders facing their course and weighted 3 times, 0.5 changed no run of
  // transport_composition by more than 3 ticks.
  double leader_reach_m = 0.0;
  // The object's centre during transport: the mission robots' current centroid (the evaluated
  // code: the rectangle jumps onto the robots when transport starts) or, false, that centroid
  // plus the offset object centre - centroid fixed at the start (the object does not jump).
  bool object_at_centroid = false;
  // (ext) A leader under its object faces its course whenever it stands there (gathering, and
  // loading: a turn in place, which a freeze allows), so that its heading shows the way from
  // the transport's first tick on - the thesis's leader is a lighthouse that permanently shows
  // a direction (5.2). false: it faces where it came from until its first transport tick.
  bool leaders_face_course = true;
  // (ext) Gathering ends when every robot is under the object and the group is one chain at the
  // local range. At the evaluated code's range 4.0 that is the same as "all inside"; at 1.0 a
  // last robot stopping at the rim can start the transport out of its group's reach.
  bool gather_one_chain = true;
  // (ext) In a swarm transport each leader's heading counts this many times in a passive
  // robot's alignment: the thesis's stacking (outlook, 8.2.1), k - 1 virtual copies at the
  // leader's pose, as its group sees them. 1 = the evaluated code, where n passive robots
  // whose headings happen to agree outvote their leaders at the first tick.
  int transport_leader_weight = 4;
  // Swarm transport (ext): within this distance of the target (m; 0: never) every mission
  // robot's speed shrinks in proportion to the object's distance to go, so that the swarm's
  // alignment, which lags its leaders' course by a few ticks, does not carry the object past
  // the tolerance; after an overshoot the leaders' course turns by ~180 degrees, where
  // alignment hardly pulls at all, and the swarm runs off with the object. 0.2 costs a run
  // about 1 tick; 0.5 cost 6; 0.1 and 0 let 1-5 of 15 runs overshoot and never finish.
  double approach_radius_m = 0.2;
  // Formation: the body moves at this fraction of the speed; a robot out of place drives up to
  // the full speed to rejoin its place.
  double formation_speed_fraction = 0.98;
  // Formation: a robot this close to its place (m) moves exactly with the body.
  double formation_slack_m = 0.02;

  // Empty when valid, else one sentence naming the first bad field.
  std::string Validate() const;
};

// What a mission robot knows of its object this tick (MissionAgent fills it).
struct Carry {
  bool transport = false;  // false: gathering (or loading)
  bool loading = false;    // the group is frozen under the object, waiting for LOADED
  TransportMode mode = TransportMode::kSwarm;
  bool leader = false;
  Shape object;  // at `centre`
  Vec2 centre;   // current: offset at transport start + centroid of the mission's robots
  Vec2 target;
  double goal_tolerance_m = 0.05;
  Vec2 formation_offset;  // formation: its place relative to the centre, fixed at the start
  std::vector<std::uint16_t> peers;    // the mission's other robots, ascending
  std::vector<std::uint16_t> leaders;  // the mission's leaders, ascending
  // Gathering by a plan (gather_planner not nearest): its own slot under the object.
  std::optional<Vec2> slot;
  // Gathering around static danger zones (issue 27, item 7): the next waypoint of its way to its
  // slot (or the object's centre) while that goal is not in clear sight; none: no zone in the way.
  std::optional<Vec2> via;

  bool Arrived() const { return transport && Distance(centre, target) <= goal_tolerance_m; }
};

// One tick of a mission robot, in this order: arrived -> stand; formation -> drive to its place
// in the body moving along object centre -> target; outside the object -> straight for its
// centre (no noise, no alignment; leaders too unless unbound) - but gathering with a waypoint
// (`via`) -> for the waypoint first, around robots in the way; gathering with a slot -> straight
// for the slot, swerving around robots in the way (inside the object only onto moves that stay
// inside), standing on it; gathering without -> hold or fill;
// transport leader -> the bearing object centre -> target, destination inside the object,
// slower on each blocked try, else turn to that bearing and hold; transport passive ->
// alignment, free will and cohesion over its chain with the point lookahead steps ahead inside
// the object, +-180 degree search, slower after each failed search. Draws exactly one
// free-will sample from `rng`, like FlockingStep.
MoveDecision CarryStep(const Perception& in, const FlockingParams& p, const TransportParams& tp,
                       const Carry& carry, Rng& rng, double duration_s);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_TRANSPORT_H_
