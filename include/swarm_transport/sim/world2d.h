// The simulated world: a pure fixed-step 2D kinematic world of disc robots (no ROS, no clock).
#ifndef SWARM_TRANSPORT_SIM_WORLD2D_H_
#define SWARM_TRANSPORT_SIM_WORLD2D_H_

#include <boost/container/flat_map.hpp>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/core/kinematics.h"
#include "swarm_transport/core/modes.h"
#include "swarm_transport/core/random.h"
#include "swarm_transport/sim/spatial_grid.h"

namespace swarm_transport {
namespace sim {

// Parameters of the world, with units in the names.
struct WorldParams {
  double world_size_m = 11.088889;   // side of the square arena [0, size]^2 (turtlesim's size)
  double robot_radius_m = 0.05;      // disc radius of every robot
  double integration_step_s = 0.01;  // longest sub-step of Step()
  double command_duration_s = 1.0;   // a command is held this long, then the robot stands
                                     // (turtlesim: 1 s; the simulator node uses the tick period)
  bool push_apart = true;            // separate overlapping robots after every Step()

  // Empty when valid, else one sentence naming the first bad field and the accepted range.
  std::string Validate() const;
};

// One robot of the world.
struct Robot {
  std::uint16_t id = 0;
  core::Pose2 pose;
  core::Pose2 spawn_pose;            // where Reset() puts it back
  core::Velocity command;            // the held command (zero once it expired)
  double command_remaining_s = 0.0;  // how much longer `command` is held
  core::Velocity last_velocity;      // what it drove with in the last sub-step (zero: stood)
  core::HeadingTrig trig;            // Step's cos / sin of its heading (a cache, not state)
};

// A square arena of unicycle disc robots, advanced only by Step(dt). The same state and the
// same commands always give bit-identical results: nothing depends on a clock, on hashing or on
// the order in which commands were set.
class World2D {
 public:
  // `params` must be valid (see WorldParams::Validate).
  explicit World2D(const WorldParams& params);

  const WorldParams& params() const { return params_; }

  // Adds robot `id` at `pose`. Fails (state unchanged, `error` says why) when the id is in use,
  // a value is not finite, or the centre is outside [r, size - r]^2.
  bool Spawn(std::uint16_t id, const core::Pose2& pose, std::string* error);
  // Removes robot `id`; fails when it does not exist.
  bool Kill(std::uint16_t id, std::string* error);
  // Puts robot `id` at `pose` (same checks as Spawn). The held command is kept.
  bool TeleportAbsolute(std::uint16_t id, const core::Pose2& pose, std::string* error);
  // Turns robot `id` by `angular_rad`, then moves it `linear_m` forward along the new heading;
  // the result is clamped into the arena (the border is a wall, as in turtlesim).
  bool TeleportRelative(std::uint16_t id, double linear_m, double angular_rad, std::string* error);
  // Replaces robot `id`'s command; it is held for command_duration_s of simulated time.
  bool SetCommand(std::uint16_t id, core::Velocity velocity, std::string* error);
  // The same for the robot at `index` of robots() (no search by id: a batch run sets every
  // robot's command each tick); fails when there is no such robot.
  bool SetCommandAt(std::size_t index, core::Velocity velocity, std::string* error);

  // Advances every robot by `dt_s` (>= 0) in equal sub-steps of at most integration_step_s;
  // within a sub-step a robot drives the exact arc of its command for as long as the command
  // is still held. Afterwards centres are clamped into the arena and, unless
  // `resolve_contacts` is false, overlapping robots are pushed apart (ResolveContacts).
  void Step(double dt_s, bool resolve_contacts = true);
  // Overlapping robots pushed apart (pairs in id order, then clamped again; up to 5 passes).
  void ResolveContacts();
  // Every robot back to its spawn pose, commands cleared.
  void Reset();

  // All robots, sorted by id, in one array (a map's node per robot cost a tenth of a real-time
  // process at 2,000 robots in traversals alone: the simulator walks them every 10 ms step).
  using RobotMap = boost::container::flat_map<std::uint16_t, Robot>;
  const RobotMap& robots() const { return robots_; }
  // The robot with `id`, or nullptr.
  const Robot* Find(std::uint16_t id) const;
  std::size_t size() const { return robots_.size(); }

  // For every robot in robots() order, the ids (ascending) of the other robots whose centre is
  // within `range_m` (distance <= range_m) of its centre. A uniform grid makes it O(N) for
  // bounded density. Empty lists when range_m is not > 0.
  std::vector<std::vector<std::uint16_t>> NeighbourLists(double range_m) const;
  // The same by index into robots() order, in one table that keeps its memory between calls
  // (the radio asks every tick): robot i's neighbours are index[start[i] .. start[i + 1]).
  struct NeighbourTable {
    std::vector<std::uint32_t> start;  // robots() + 1 entries
    std::vector<std::uint32_t> index;  // ascending within each robot's range
    // The search's scratch (kept for the next call).
    std::vector<core::Vec2> points;
    SpatialGrid grid;
  };
  void NeighbourIndices(double range_m, NeighbourTable* out) const;

 private:
  bool Inside(const core::Pose2& pose, std::string* error) const;
  core::Vec2 Clamped(core::Vec2 p) const;
  void ClampAll();
  // SetCommand's checks and effect on `robot`.
  bool ApplyCommand(Robot* robot, core::Velocity velocity, std::string* error) const;
  // One pass over all overlapping pairs; false when there was none. `touched`: on entry the
  // robots (by index) moved by the pass before, to search around (empty: every robot); on exit
  // the robots this pass pushed. A pair that overlaps now has a robot moved by the pass before
  // (two unmoved robots that overlapped would have been pushed) or is one of that pass's pairs
  // left alone at the contact distance: searching around the moved robots and keeping those
  // pairs finds every pair a search around all robots would (bit for bit the same result).
  // Uses ResolveContacts' robots and their current positions (push_order_, push_points_).
  bool PushApartOnce(std::vector<std::uint8_t>* touched);
  // The contact grid of every robot where it is now; none moved since.
  void BuildContactGrid();

  WorldParams params_;
  RobotMap robots_;
  // PushApartOnce's scratch, kept between calls (it runs up to 5 times per ResolveContacts).
  std::vector<Robot*> push_order_;
  std::vector<core::Vec2> push_points_;
  std::vector<std::pair<std::size_t, std::size_t>> push_pairs_;
  std::vector<std::uint8_t> push_touched_;
  SpatialGrid push_grid_;  // every robot, where it was at its build
  // The robots moved since push_grid_'s build (flags by index, and their list), and a grid of
  // their current positions (index into the list).
  std::vector<std::uint8_t> push_moved_;
  std::vector<std::size_t> push_moved_list_;
  std::vector<core::Vec2> push_moved_points_;
  SpatialGrid push_moved_grid_;
};

// Poses of `n` robots at random positions inside [r, size - r]^2, centres at least
// 2 r * 1.1 * 1.5 apart, with random headings; the same seed gives the same poses. Empty with
// `error` set when they do not fit.
std::vector<core::Pose2> PlaceRandom(int n, std::uint64_t seed, const WorldParams& params,
                                     std::string* error = nullptr);

// A pose for one more robot: a random point of the arena (drawn from `rng`) where it overlaps
// no robot of `world`, facing a random heading. False when none was found in a bounded number
// of attempts (a full arena).
bool FreePose(const World2D& world, core::Rng* rng, core::Pose2* pose);

// Poses of `n` robots clustered on a square grid of spacing 3 r in the bottom-left corner,
// heading 45 degrees. Empty with `error` set when they do not fit.
std::vector<core::Pose2> PlaceCorner(int n, const WorldParams& params,
                                     std::string* error = nullptr);

// Parses a placement file: one robot per line "x y theta_deg", '#' starts a comment, blank lines
// are skipped. False with `error` naming the line when a line is malformed or not finite.
bool ParsePlacement(const std::string& text, std::vector<core::Pose2>* poses, std::string* error);

// Spawns the initial robots, ids 0..n-1, into an empty `world`: `*robots` of them placed by
// `placement` (random with `seed`, corner, or the lines of `placement_file`; with a file,
// *robots < 0 takes every line and is set to their number). False with `error` naming what is
// wrong (a file that cannot be read, too few poses, a pose outside the arena).
bool PlaceInitialRobots(core::Placement placement, std::uint64_t seed,
                        const std::string& placement_file, int* robots, World2D* world,
                        std::string* error);

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_WORLD2D_H_
