#include "swarm_transport/core/run_metrics_gathering.h"

#include "swarm_transport/core/assignment.h"

namespace swarm_transport {
namespace core {

void GatheringMetrics::AddMove(const std::optional<Carry>& carry, bool frozen, Vec2 position,
                               MoveOutcome outcome) {
  if (!carry || carry->transport || carry->loading || frozen) return;
  if (outcome == MoveOutcome::kStraight) return;
  const bool placed =
      carry->slot ? Distance(position, *carry->slot) <= kPlacedM : carry->object.Contains(position);
  if (!placed) ++interference_;
}

void GatheringMetrics::AddPlan(const GatherPlanRecord& record) {
  if (!seen_.emplace(record.mission_id, record.tick).second) return;
  if (!record.plan.stable) ++unstable_;
  const CostMatrix x = SelectionMatrix(record.robots, record.targets, record.params);
  double chosen = 0.0;
  for (std::size_t m = 0; m < record.plan.target_of.size() && m < x.rows; ++m) {
    const int n = record.plan.target_of[m];
    if (n >= 0) chosen += x.at(m, static_cast<std::size_t>(n));
  }
  const double least = Hungarian(x).total;
  ratios_.push_back(least > 0.0 ? chosen / least : 1.0);
}

}  // namespace core
}  // namespace swarm_transport
