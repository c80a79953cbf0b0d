#include "swarm_transport/core/plan_arrival.h"

#include <algorithm>
#include <cmath>

#include "swarm_transport/core/metrics.h"

namespace swarm_transport {
namespace core {
namespace {

// Two plans give the same slot when they name the same point (slots are computed, not measured).
constexpr double kSameSlotM = 1e-6;

}  // namespace

void PlanArrivals::Plan(std::uint16_t id, std::uint64_t tick, Vec2 slot, double x) {
  const auto it = estimates_.find(id);
  if (it != estimates_.end()) {
    if (Distance(it->second.slot, slot) <= kSameSlotM) return;  // the first plan of it counts
    ++slot_changes_;
  }
  Estimate e;
  e.slot = slot;
  e.tick = tick;
  e.planned = static_cast<double>(tick) + x;
  estimates_[id] = e;
}

void PlanArrivals::At(std::uint16_t id, std::uint64_t tick, Vec2 position) {
  const auto it = estimates_.find(id);
  if (it == estimates_.end() || it->second.arrived || tick < it->second.tick) return;
  if (Distance(position, it->second.slot) <= placed_m_) it->second.arrived = tick;
}

std::vector<double> PlanArrivals::Errors() const {
  std::vector<double> errors;
  for (const auto& kv : estimates_) {
    const Estimate& e = kv.second;
    if (e.arrived) errors.push_back(static_cast<double>(*e.arrived) - e.planned);
  }
  return errors;
}

std::size_t PlanArrivals::unarrived() const {
  return static_cast<std::size_t>(
      std::count_if(estimates_.begin(), estimates_.end(),
                    [](const auto& kv) { return !kv.second.arrived.has_value(); }));
}

ErrorSummary Summarize(const std::vector<double>& errors) {
  ErrorSummary s;
  if (errors.empty()) return s;
  std::vector<double> abs;
  for (double e : errors) abs.push_back(std::fabs(e));
  s.median_abs = Median(abs);
  s.max_abs = *std::max_element(abs.begin(), abs.end());
  s.median = Median(errors);
  return s;
}

}  // namespace core
}  // namespace swarm_transport
