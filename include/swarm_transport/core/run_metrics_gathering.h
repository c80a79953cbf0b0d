// (ext, issue 27) What a run's gathering costs beyond its ticks, counted by the batch engine from
// the robots' moves and plans: the interference between robots that are not placed yet, and
// the plans of a planned gathering (transport.gather_planner): how many hit the round cap, and
// how far their total time X lies above the least possible (Hungarian) on the same matrix. Pure.
#ifndef SWARM_TRANSPORT_CORE_RUN_METRICS_GATHERING_H_
#define SWARM_TRANSPORT_CORE_RUN_METRICS_GATHERING_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/core/flocking.h"
#include "swarm_transport/core/mission_agent.h"
#include "swarm_transport/core/plan_arrival.h"
#include "swarm_transport/core/transport.h"

namespace swarm_transport {
namespace core {

class GatheringMetrics {
 public:
  // A robot with its own slot counts as placed within this distance of it.
  static constexpr double kPlacedM = 0.01;
  // LeadersBehind's tolerance in the result (a robot radius).
  static constexpr double kFrontToleranceM = 0.05;

  // One robot's move of a tick, from `position` (where it stood when it decided): counted as
  // interference when the robot gathers (a carry, not in transport, not loading, not frozen),
  // is not placed yet (with a slot: not on it; without: outside the object) and the move
  // swerved, slowed or stood (a robot not placed stands only when something is in its way).
  void AddMove(const std::optional<Carry>& carry, bool frozen, Vec2 position, MoveOutcome outcome);
  // The last plan robot `self` made: the plan metrics count the first record of each mission
  // and tick (every member makes the same plan from what it hears); the arrival estimates take
  // each robot's own slot and X from its own plan.
  void AddPlan(std::uint16_t self, const GatherPlanRecord& record);
  // Robot `self` stands at `position` at `tick` (its round's pose; after the tick's AddPlan):
  // its arrival on its slot, looked for until its transport begins.
  void AddPosition(std::uint16_t self, std::uint64_t tick, const std::optional<Carry>& carry,
                   Vec2 position);

  std::uint64_t interference() const { return interference_; }
  std::size_t plans() const { return ratios_.size(); }
  std::size_t unstable_plans() const { return unstable_; }
  // Per plan: sum of X (SelectionMatrix, without corrections) of its pairs over the least such
  // sum (Hungarian on the same X); 1 when both are 0.
  const std::vector<double>& cost_ratios() const { return ratios_; }
  // Planned against actual arrivals on the slots (the first plan of each robot's final slot).
  const PlanArrivals& arrivals() const { return arrivals_; }
  // (issue 27, item 6) Where the robots stand when their transport begins (each robot at the
  // first tick its carry is in transport): the non-leaders standing more than `tolerance_m`
  // further toward the transport's target (the projection of position - object centre onto the
  // direction to the target) than the rearmost leader; 0: the leaders stand at the front.
  // std::nullopt before any transport began or without a leader or a non-leader.
  std::optional<std::size_t> LeadersBehind(double tolerance_m) const;
  // The run's result members of issue 27's items 3 and 6, by name: leaders_behind (with
  // kFrontToleranceM, when known); with plans, plan_arrival_error_ticks / _max /
  // plan_arrival_late_ticks (Summarize of the arrivals' errors, when any robot arrived),
  // plan_unarrived and plan_slot_changes.
  std::vector<std::pair<std::string, double>> ResultFields() const;

 private:
  std::uint64_t interference_ = 0;
  std::size_t unstable_ = 0;
  std::vector<double> ratios_;
  std::set<std::pair<std::uint16_t, std::uint64_t>> seen_;  // (mission, tick) of plans counted
  PlanArrivals arrivals_{kPlacedM};
  std::map<std::uint16_t, std::pair<bool, double>> front_;  // at transport start: leader, ahead
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_RUN_METRICS_GATHERING_H_
