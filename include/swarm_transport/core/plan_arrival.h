// (ext, issue 27, item 3) Is a plan's X a realistic time estimate? Each robot's planned arrival
// on its slot (the plan's tick + its X with the corrections, in ticks) against the tick it first
// stands on that slot. Pure.
#ifndef SWARM_TRANSPORT_CORE_PLAN_ARRIVAL_H_
#define SWARM_TRANSPORT_CORE_PLAN_ARRIVAL_H_

#include <cstddef>
#include <cstdint>
#include <map>
#include <optional>
#include <vector>

#include "swarm_transport/core/geometry.h"

namespace swarm_transport {
namespace core {

// Which plan's estimate counts: the first plan of a robot's final slot. A robot's estimate is
// taken from the first plan that gives it a slot and kept while later plans give it the same
// slot (a replan that keeps the slot does not reset it); a plan that gives it another slot
// starts a new estimate (a slot change) and forgets an arrival on the old slot. The robot
// arrives at the first tick, at or after that plan's tick, at which it stands within placed_m
// of its slot.
class PlanArrivals {
 public:
  explicit PlanArrivals(double placed_m) : placed_m_(placed_m) {}

  // A plan made at `tick` gives robot `id` the slot at `slot`, estimated `x` ticks away.
  void Plan(std::uint16_t id, std::uint64_t tick, Vec2 slot, double x);
  // Robot `id` stands at `position` at `tick` (call a tick's plans before its positions).
  void At(std::uint16_t id, std::uint64_t tick, Vec2 position);

  // Per robot that arrived on its final slot (ascending id): actual - planned arrival in ticks
  // (> 0: later than planned).
  std::vector<double> Errors() const;
  // Robots with a slot that never stood on their final one.
  std::size_t unarrived() const;
  // Plans that gave a robot a slot other than the one it had.
  std::size_t slot_changes() const { return slot_changes_; }

 private:
  struct Estimate {
    Vec2 slot;
    std::uint64_t tick = 0;
    double planned = 0.0;  // tick + x
    std::optional<std::uint64_t> arrived;
  };
  double placed_m_;
  std::map<std::uint16_t, Estimate> estimates_;
  std::size_t slot_changes_ = 0;
};

// The median and the largest of |errors| (both 0 when there are none).
struct ErrorSummary {
  double median_abs = 0.0;
  double max_abs = 0.0;
  double median = 0.0;  // signed: > 0 when robots arrive later than planned
};
ErrorSummary Summarize(const std::vector<double>& errors);

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_PLAN_ARRIVAL_H_
