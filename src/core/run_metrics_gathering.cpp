#include "swarm_transport/core/run_metrics_gathering.h"

#include <algorithm>

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

void GatheringMetrics::AddPlan(std::uint16_t self, const GatherPlanRecord& record) {
  for (std::size_t k = 0; k < record.ids.size() && k < record.plan.target_of.size(); ++k) {
    const int n = record.plan.target_of[k];
    if (record.ids[k] != self || n < 0) continue;
    arrivals_.Plan(self, record.tick, record.targets[static_cast<std::size_t>(n)].position,
                   record.plan.time[k]);
  }
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

void GatheringMetrics::AddPosition(std::uint16_t self, std::uint64_t tick,
                                   const std::optional<Carry>& carry, Vec2 position) {
  if (carry && !carry->transport) arrivals_.At(self, tick, position);
  if (carry && carry->transport && front_.count(self) == 0) {
    const Vec2 to = carry->target - carry->centre;
    const double length = Norm(to);
    const Vec2 from = position - carry->centre;
    const double ahead = length > 0.0 ? (from.x * to.x + from.y * to.y) / length : 0.0;
    front_.emplace(self, std::make_pair(carry->leader, ahead));
  }
}

std::optional<std::size_t> GatheringMetrics::LeadersBehind(double tolerance_m) const {
  std::optional<double> rearmost;
  for (const auto& kv : front_) {
    if (kv.second.first) rearmost = std::min(rearmost.value_or(kv.second.second), kv.second.second);
  }
  std::size_t others = 0;
  std::size_t ahead = 0;
  for (const auto& kv : front_) {
    if (kv.second.first) continue;
    ++others;
    if (rearmost && kv.second.second > *rearmost + tolerance_m) ++ahead;
  }
  if (!rearmost || others == 0) return std::nullopt;
  return ahead;
}

std::vector<std::pair<std::string, double>> GatheringMetrics::ResultFields() const {
  std::vector<std::pair<std::string, double>> fields;
  const std::optional<std::size_t> behind = LeadersBehind(kFrontToleranceM);
  if (behind) fields.emplace_back("leaders_behind", static_cast<double>(*behind));
  if (plans() == 0) return fields;
  const std::vector<double> errors = arrivals_.Errors();
  if (!errors.empty()) {
    const ErrorSummary e = Summarize(errors);
    fields.emplace_back("plan_arrival_error_ticks", e.median_abs);
    fields.emplace_back("plan_arrival_error_max", e.max_abs);
    fields.emplace_back("plan_arrival_late_ticks", e.median);
  }
  fields.emplace_back("plan_unarrived", static_cast<double>(arrivals_.unarrived()));
  fields.emplace_back("plan_slot_changes", static_cast<double>(arrivals_.slot_changes()));
  return fields;
}

}  // namespace core
}  // namespace swarm_transport
