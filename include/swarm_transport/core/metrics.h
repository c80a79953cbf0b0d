// Swarm metrics of the thesis's evaluation [SPEC 8, T7]: swarm count, transport slip,
// distance and leader waits, leader success, and the statistics over repeated runs.
#ifndef SWARM_TRANSPORT_CORE_METRICS_H_
#define SWARM_TRANSPORT_CORE_METRICS_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include "swarm_transport/core/geometry.h"

namespace swarm_transport {
namespace core {

// A tick in which a leader moved less than this (m) is a leader wait [T7.3, T7.4].
constexpr double kLeaderWaitM = 1e-6;

// The swarms of a set of robots [T7.2, Fig. 7.1]: connected components of the graph linking
// every two robots at most `local_range_m` apart (a chain of mutually influencing robots).
// A uniform grid of cell local_range_m finds the pairs, so thousands of robots are fast.
// Non-finite positions, and every position when local_range_m is not > 0, are swarms of one.
class SwarmComponents {
 public:
  SwarmComponents(const std::vector<Vec2>& positions, double local_range_m);

  // Number of swarms (0 for no robots).
  std::size_t SwarmCount() const { return sizes_.size(); }
  // The swarm of robot `index` (an index into the positions): 0 .. SwarmCount()-1, numbered
  // in the order of each swarm's lowest index.
  std::size_t ComponentOf(std::size_t index) const { return labels_.at(index); }
  // Robots in swarm `component`.
  std::size_t ComponentSize(std::size_t component) const { return sizes_.at(component); }
  // Robots in the swarm of robot `index` (itself included).
  std::size_t SizeOfSwarmOf(std::size_t index) const { return sizes_.at(labels_.at(index)); }
  // Robots in the largest swarm (0 for no robots).
  std::size_t LargestSwarm() const;
  // ComponentOf for every robot.
  const std::vector<std::size_t>& labels() const { return labels_; }

 private:
  std::vector<std::size_t> labels_;
  std::vector<std::size_t> sizes_;
};

// How a swarm spreads over the arena [SPEC 9.5, balloon dispersion], from one frame.
struct Dispersion {
  // Fraction of the arena's square cells (side cell_m) whose centre lies within
  // cover_radius_m of a robot: the area the swarm covers, 0 for no robots.
  double coverage_fraction = 0.0;
  // Mean distance from each robot to its nearest other robot (m), and the coefficient of
  // variation of those distances (standard deviation / mean: 0 = evenly spaced); NaN for fewer
  // than two robots.
  double nn_mean_m = 0.0;
  double nn_cv = 0.0;
};
// For each of the (finite) positions, Distance() to its nearest other one (+inf when there is
// no other): bit for bit the minimum over every pair, found with a k-d tree in O(N log N)
// instead of comparing all N^2 / 2 pairs.
std::vector<double> NearestNeighbourDistances(const std::vector<Vec2>& positions);
// Non-finite positions are left out.
Dispersion DispersionOf(const std::vector<Vec2>& positions, double world_size_m,
                        double cover_radius_m, double cell_m);

// Plain mean; NaN for no values.
double Mean(const std::vector<double>& values);
// Median (mean of the two middle values for an even count); NaN for no values.
double Median(std::vector<double> values);
// The thesis's mean over the middle runs [T7.1]: sorts, drops floor((n - middle) / 2) values
// from each end and averages the rest (middle + 1 values remain when n - middle is odd).
// middle >= n or middle == 0: the plain mean. 10 runs, middle 6; 15 runs, middle 11 or 9.
double TrimmedMean(std::vector<double> values, std::size_t middle);
// The default of the project: drop the 2 lowest and the 2 highest runs (n < 5: the plain
// mean), which is what the thesis did with its runs: 10 -> middle 6 [T7.2], 15 -> middle 11
// [T7.3, T7.4].
double TrimmedMean(std::vector<double> values);

// Transport metrics of one mission [T7.4], fed once per tick while it is in TRANSPORT with the
// positions of its assigned robots (always the same robots in the same order).
// Slip: per tick each robot's movement relative to the object centre. The object centre is a
// fixed offset plus the centroid of the assigned robots [SPEC 6.6], so its movement is the
// centroid's: slip_i += |dp_i - dcentroid|. Distance: distance_i += |dp_i|. Both are averaged
// over the robots. A leader wait is one leader in one tick moving less than kLeaderWaitM.
// Leader contact: of the passive robots' ticks (the same ticks), the fraction in which the
// robot had a leader within contact_range_m (its local range), i.e. could align with one.
class TransportTracker {
 public:
  explicit TransportTracker(double contact_range_m = 0.0) : contact_range_m_(contact_range_m) {}

  // One tick. The first call sets the start; each later call with a larger tick adds the
  // movement since the previous call (missed ticks in between count as ticks). False (and no
  // change) when the call does not fit: empty positions, sizes differing from each other or
  // from the first call, a non-finite position, or a tick not after the previous one.
  bool Feed(std::uint64_t tick, const std::vector<Vec2>& positions,
            const std::vector<bool>& is_leader);

  bool started() const { return started_; }
  // Ticks from the first to the last fed tick.
  std::uint64_t ticks() const { return last_tick_ - first_tick_; }
  // Mean over the robots of the summed slip (m); 0 before two ticks.
  double SlipPerRobot() const;
  // Mean over the robots of the summed distance driven (m); 0 before two ticks.
  double DistancePerRobot() const;
  // Leader waits summed over all leaders.
  std::uint64_t LeaderWaits() const { return leader_waits_; }
  // Fraction in [0, 1] of passive robot-ticks with a leader in contact range; nullopt without
  // passive robots, before two ticks, or without a contact range (> 0).
  std::optional<double> LeaderContact() const;

 private:
  bool started_ = false;
  std::uint64_t first_tick_ = 0;
  std::uint64_t last_tick_ = 0;
  std::vector<Vec2> previous_;
  double slip_sum_ = 0.0;      // over robots and ticks
  double distance_sum_ = 0.0;  // over robots and ticks
  std::uint64_t leader_waits_ = 0;
  double contact_range_m_ = 0.0;
  std::uint64_t passive_ticks_ = 0;  // over passive robots and ticks
  std::uint64_t contact_ticks_ = 0;  // ... with a leader within contact_range_m_
};

// Leader success of one leader-only mission [T7.3], fed once per tick from its start until
// the leader arrived, with every robot's position. The path fraction with the whole swarm
// attached is the part of the straight start -> target distance the leader had covered,
// 1 - distance_to_target / start_distance_to_target clamped to [0, 1], at the first fed tick
// in which its swarm (SwarmComponents) lacked any robot; 1 if that never happened. A zero
// start distance counts as a covered path.
class LeaderTracker {
 public:
  LeaderTracker(Vec2 target, double local_range_m);

  // One tick: all robots' positions and the leader's index among them. The first call sets
  // the start. False (and no change) when the call does not fit: the leader index out of
  // range, the leader's position not finite, or a tick not after the previous one.
  bool Feed(std::uint64_t tick, const std::vector<Vec2>& positions, std::size_t leader);

  bool started() const { return started_; }
  std::uint64_t ticks() const { return last_tick_ - first_tick_; }
  // In [0, 1]; 1 until the swarm first lacked a robot.
  double PathFractionAttached() const { return path_fraction_; }
  // True once the leader's swarm lacked a robot in a fed tick.
  bool lost_swarm() const { return lost_; }
  // Robots in the leader's swarm at the last fed tick, the leader excluded.
  std::size_t SwarmAtLastTick() const { return swarm_at_last_; }
  // Ticks in which the leader moved less than kLeaderWaitM.
  std::uint64_t LeaderWaits() const { return waits_; }
  // The leader's distance to the target at the last fed tick (m).
  double DistanceToTarget() const { return distance_to_target_; }

 private:
  Vec2 target_;
  double local_range_m_;
  bool started_ = false;
  std::uint64_t first_tick_ = 0;
  std::uint64_t last_tick_ = 0;
  Vec2 start_;
  Vec2 previous_;
  bool lost_ = false;
  double path_fraction_ = 1.0;
  std::size_t swarm_at_last_ = 0;
  std::uint64_t waits_ = 0;
  double distance_to_target_ = 0.0;
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_METRICS_H_
