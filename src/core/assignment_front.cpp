// Leaders to the front slots (issue 27, item 6): PlanLeadersInFront.
#include <algorithm>
#include <cmath>
#include <numeric>

#include "swarm_transport/core/assignment.h"

namespace swarm_transport {
namespace core {
namespace {

// One part's plan (robots `rows`, targets `cols` of the whole) written into the whole plan.
void Merge(const SelectionPlan& part, const std::vector<std::size_t>& rows,
           const std::vector<std::size_t>& cols, SelectionPlan* whole) {
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::size_t m = rows[i];
    const int n = part.target_of[i];
    whole->target_of[m] = n < 0 ? -1 : static_cast<int>(cols[static_cast<std::size_t>(n)]);
    whole->time[m] = part.time[i];
    whole->blocked[m] = part.blocked[i];
    whole->crossing[m] = part.crossing[i];
    if (n >= 0) {
      whole->total += part.time[i];
      whole->last = std::max(whole->last, part.time[i]);
    }
  }
  whole->rounds = std::max(whole->rounds, part.rounds);
  whole->frozen += part.frozen;
}

}  // namespace

SelectionPlan PlanLeadersInFront(const std::vector<PlannerRobot>& robots,
                                 const std::vector<bool>& is_leader,
                                 const std::vector<PlannerTarget>& targets, Vec2 centre,
                                 Vec2 course, const SelectionParams& p, const Planner& plan) {
  std::vector<std::size_t> leaders, others;
  for (std::size_t m = 0; m < robots.size(); ++m) {
    (m < is_leader.size() && is_leader[m] ? leaders : others).push_back(m);
  }
  if (leaders.empty() || targets.size() < robots.size()) return plan(robots, targets, p);
  // Targets by how far along the course they lie (rounded to 1e-9 m), furthest first.
  std::vector<double> ahead(targets.size());
  for (std::size_t n = 0; n < targets.size(); ++n) {
    const Vec2 off = targets[n].position - centre;
    ahead[n] = std::round((off.x * course.x + off.y * course.y) * 1e9) / 1e9;
  }
  std::vector<std::size_t> order(targets.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return ahead[a] > ahead[b]; });
  std::size_t front = leaders.size();
  while (front < order.size() && ahead[order[front]] == ahead[order[front - 1]]) ++front;
  std::vector<std::size_t> front_cols(order.begin(), order.begin() + static_cast<long>(front));
  std::sort(front_cols.begin(), front_cols.end());
  const auto part = [&](const std::vector<std::size_t>& rows,
                        const std::vector<std::size_t>& cols) {
    std::vector<PlannerRobot> r;
    std::vector<PlannerTarget> t;
    for (std::size_t m : rows) r.push_back(robots[m]);
    for (std::size_t n : cols) t.push_back(targets[n]);
    return plan(r, t, p);
  };
  SelectionPlan whole;
  whole.target_of.assign(robots.size(), -1);
  whole.time.assign(robots.size(), 0.0);
  whole.blocked.assign(robots.size(), 0.0);
  whole.crossing.assign(robots.size(), 0.0);
  const SelectionPlan first = part(leaders, front_cols);
  Merge(first, leaders, front_cols, &whole);
  std::vector<std::size_t> rest;
  for (std::size_t n = 0; n < targets.size(); ++n) {
    if (std::find(whole.target_of.begin(), whole.target_of.end(), static_cast<int>(n)) ==
        whole.target_of.end()) {
      rest.push_back(n);
    }
  }
  const SelectionPlan second = others.empty() ? SelectionPlan{} : part(others, rest);
  if (!others.empty()) Merge(second, others, rest, &whole);
  whole.stable = first.stable && (others.empty() || second.stable);
  return whole;
}

}  // namespace core
}  // namespace swarm_transport
