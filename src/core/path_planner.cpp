#include "swarm_transport/core/path_planner.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

namespace swarm_transport {
namespace core {
namespace {

bool PointClear(Vec2 q, const std::vector<Zone>& zones, const PathParams& p) {
  if (q.x < 0.0 || q.y < 0.0 || q.x > p.world_size_m || q.y > p.world_size_m) return false;
  for (const Zone& z : zones) {
    if (z.Forbids(q)) return false;
    if (!z.inverted && z.shape.DistanceTo(q) < p.clearance_m) return false;
  }
  return true;
}

}  // namespace

bool SegmentClear(Vec2 a, Vec2 b, const std::vector<Zone>& zones, const PathParams& p) {
  const double length = Distance(a, b);
  const int steps = std::max(1, static_cast<int>(std::ceil(length / (p.cell_m / 2.0))));
  for (int i = 0; i <= steps; ++i) {
    const double t = static_cast<double>(i) / steps;
    if (!PointClear(a + (b - a) * t, zones, p)) return false;
  }
  return true;
}

std::optional<std::vector<Vec2>> PlanPath(Vec2 from, Vec2 to, const std::vector<Zone>& zones,
                                          const PathParams& p) {
  if (!PointClear(to, zones, p)) return std::nullopt;
  // The straight line, except where it starts inside a zone's clearance (a start at the border
  // may leave it by the shortest way).
  if (SegmentClear(from, to, zones, p)) return std::vector<Vec2>{to};
  const int n = std::max(2, static_cast<int>(std::ceil(p.world_size_m / p.cell_m)));
  const double cell = p.world_size_m / n;
  const auto centre = [&](int i, int j) { return Vec2{(i + 0.5) * cell, (j + 0.5) * cell}; };
  const auto index_of = [&](Vec2 q) {
    const int i = std::clamp(static_cast<int>(q.x / cell), 0, n - 1);
    const int j = std::clamp(static_cast<int>(q.y / cell), 0, n - 1);
    return std::make_pair(i, j);
  };
  std::vector<char> blocked(static_cast<std::size_t>(n) * n, 0);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) blocked[i * n + j] = PointClear(centre(i, j), zones, p) ? 0 : 1;
  }
  const auto [si, sj] = index_of(from);
  const auto [gi, gj] = index_of(to);
  blocked[si * n + sj] = 0;  // the start may be at a border
  blocked[gi * n + gj] = 0;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double> cost(blocked.size(), inf);
  std::vector<int> parent(blocked.size(), -1);
  using Item = std::pair<double, int>;  // (cost + heuristic, cell)
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> open;
  const Vec2 goal = centre(gi, gj);
  cost[si * n + sj] = 0.0;
  open.push({Distance(centre(si, sj), goal), si * n + sj});
  const int goal_cell = gi * n + gj;
  while (!open.empty()) {
    const auto [f, c] = open.top();
    open.pop();
    if (c == goal_cell) break;
    const int ci = c / n;
    const int cj = c % n;
    if (f - Distance(centre(ci, cj), goal) > cost[c] + 1e-12) continue;  // a stale entry
    for (int di = -1; di <= 1; ++di) {
      for (int dj = -1; dj <= 1; ++dj) {
        const int ni = ci + di;
        const int nj = cj + dj;
        if ((di == 0 && dj == 0) || ni < 0 || nj < 0 || ni >= n || nj >= n) continue;
        const int nc = ni * n + nj;
        if (blocked[nc]) continue;
        // No corner cutting past a blocked cell.
        if (di != 0 && dj != 0 && (blocked[ci * n + nj] || blocked[ni * n + cj])) continue;
        const double g = cost[c] + cell * std::sqrt(static_cast<double>(di * di + dj * dj));
        if (g < cost[nc]) {
          cost[nc] = g;
          parent[nc] = c;
          open.push({g + Distance(centre(ni, nj), goal), nc});
        }
      }
    }
  }
  if (cost[goal_cell] == inf) return std::nullopt;
  std::vector<Vec2> cells;
  for (int c = goal_cell; c != -1; c = parent[c]) cells.push_back(centre(c / n, c % n));
  std::reverse(cells.begin(), cells.end());
  cells.back() = to;
  // Line of sight: from each corner, the farthest cell still reachable in a straight line.
  std::vector<Vec2> waypoints;
  Vec2 at = from;
  std::size_t k = 0;
  while (k + 1 < cells.size()) {
    std::size_t far = k;
    for (std::size_t m = cells.size() - 1; m > k; --m) {
      if (SegmentClear(at, cells[m], zones, p)) {
        far = m;
        break;
      }
    }
    if (far == k) far = k + 1;  // leaving the start's clearance: one cell at a time
    at = cells[far];
    waypoints.push_back(at);
    k = far;
  }
  if (waypoints.empty() || Distance(waypoints.back(), to) > 1e-9) waypoints.push_back(to);
  return waypoints;
}

}  // namespace core
}  // namespace swarm_transport
