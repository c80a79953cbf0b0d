// (ext, issue 27) What a run's gathering costs beyond its ticks, counted by the batch engine from
// the robots' moves and plans: the interference between robots that are not placed yet, and
// the plans of a planned gathering (transport.gather_planner): how many hit the round cap, and
// how far their total time X lies above the least possible (Hungarian) on the same matrix. Pure.
#ifndef SWARM_TRANSPORT_CORE_RUN_METRICS_GATHERING_H_
#define SWARM_TRANSPORT_CORE_RUN_METRICS_GATHERING_H_

#include <cstddef>
#include <cstdint>
#include <optional>
#include <set>
#include <utility>
#include <vector>

#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/mission_agent.h"
#include "swarm_transport/core/transport.h"

namespace swarm_transport {
namespace core {

class GatheringMetrics {
 public:
  // A robot with its own slot counts as placed within this distance of it.
  static constexpr double kPlacedM = 0.01;

  // One robot's move of a tick, from `position` (where it stood when it decided): counted as
  // interference when the robot gathers (a carry, not in transport, not loading, not frozen),
  // is not placed yet (with a slot: not on it; without: outside the object) and the move
  // swerved, slowed or stood (a robot not placed stands only when something is in its way).
  void AddMove(const std::optional<Carry>& carry, bool frozen, Vec2 position, MoveOutcome outcome);
  // A plan as a member made it; every member makes the same one, so only the first record of
  // each mission and tick counts.
  void AddPlan(const GatherPlanRecord& record);

  std::uint64_t interference() const { return interference_; }
  std::size_t plans() const { return ratios_.size(); }
  std::size_t unstable_plans() const { return unstable_; }
  // Per plan: sum of X (SelectionMatrix, without corrections) of its pairs over the least such
  // sum (Hungarian on the same X); 1 when both are 0.
  const std::vector<double>& cost_ratios() const { return ratios_; }

 private:
  std::uint64_t interference_ = 0;
  std::size_t unstable_ = 0;
  std::vector<double> ratios_;
  std::set<std::pair<std::uint16_t, std::uint64_t>> seen_;  // (mission, tick) of plans counted
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_RUN_METRICS_GATHERING_H_
