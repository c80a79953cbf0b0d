#include "swarm_transport/core/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <unordered_map>
#include <utility>

namespace swarm_transport {
namespace core {
namespace {

// Grid cells beyond this index are clamped into the border cell: far-away (bad) positions
// only cost time, never a wrong link, since every candidate pair is checked by distance.
constexpr std::int64_t kMaxCell = std::int64_t{1} << 30;

// Disjoint sets with path halving and union by size.
class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n), size_(n, 1) {
    std::iota(parent_.begin(), parent_.end(), std::size_t{0});
  }
  std::size_t Find(std::size_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }
  void Union(std::size_t a, std::size_t b) {
    a = Find(a);
    b = Find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<std::size_t> parent_;
  std::vector<std::size_t> size_;
};

std::int64_t CellIndex(double coordinate, double cell) {
  const double c = std::floor(coordinate / cell);
  return static_cast<std::int64_t>(
      std::clamp(c, static_cast<double>(-kMaxCell), static_cast<double>(kMaxCell)));
}

std::uint64_t CellKey(std::int64_t cx, std::int64_t cy) {
  // Both indices fit in 32 bits after clamping.
  return (static_cast<std::uint64_t>(static_cast<std::uint32_t>(cx)) << 32) |
         static_cast<std::uint32_t>(cy);
}

bool Finite(Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); }

double MeanOfRange(std::vector<double>::const_iterator begin,
                   std::vector<double>::const_iterator end) {
  if (begin == end) return std::numeric_limits<double>::quiet_NaN();
  return std::accumulate(begin, end, 0.0) / static_cast<double>(end - begin);
}

// Nearest neighbours with a k-d tree [issue 25]: every node holds the bounding box of its
// points, a query visits the nearer child first and skips a node whose box is certainly
// farther than the best Distance() found so far. "Certainly": its squared box distance exceeds
// the best distance squared by a relative 1e-9, far more than the rounding of either, so no
// point whose computed Distance() could be below the best is skipped, and the minimum is the
// all-pairs minimum bit for bit (Distance(a, b) == Distance(b, a) exactly).
class NearestTree {
 public:
  explicit NearestTree(const std::vector<Vec2>& points) : points_(points) {
    order_.resize(points.size());
    std::iota(order_.begin(), order_.end(), std::size_t{0});
    if (!points.empty()) Build(0, points.size());
  }

  // Distance() from points[i] to its nearest other point (+inf when none).
  double Nearest(std::size_t i) const {
    double best = std::numeric_limits<double>::infinity();
    Search(0, points_[i], i, &best);
    return best;
  }

 private:
  static constexpr std::size_t kLeaf = 8;
  struct Node {
    std::size_t begin, end;  // range of order_
    double min_x, min_y, max_x, max_y;
    std::size_t left = 0, right = 0;  // children (0: a leaf; node 0 is the root)
  };

  std::size_t Build(std::size_t begin, std::size_t end) {
    Node node{begin, end, 0.0, 0.0, 0.0, 0.0};
    node.min_x = node.max_x = points_[order_[begin]].x;
    node.min_y = node.max_y = points_[order_[begin]].y;
    for (std::size_t k = begin + 1; k < end; ++k) {
      const Vec2 p = points_[order_[k]];
      node.min_x = std::min(node.min_x, p.x);
      node.max_x = std::max(node.max_x, p.x);
      node.min_y = std::min(node.min_y, p.y);
      node.max_y = std::max(node.max_y, p.y);
    }
    const std::size_t at = nodes_.size();
    nodes_.push_back(node);
    if (end - begin <= kLeaf) return at;
    // Split the wider side at the median.
    const bool by_x = node.max_x - node.min_x >= node.max_y - node.min_y;
    const std::size_t middle = begin + (end - begin) / 2;
    std::nth_element(order_.begin() + static_cast<std::ptrdiff_t>(begin),
                     order_.begin() + static_cast<std::ptrdiff_t>(middle),
                     order_.begin() + static_cast<std::ptrdiff_t>(end),
                     [this, by_x](std::size_t a, std::size_t b) {
                       return by_x ? points_[a].x < points_[b].x : points_[a].y < points_[b].y;
                     });
    const std::size_t left = Build(begin, middle);
    const std::size_t right = Build(middle, end);
    nodes_[at].left = left;
    nodes_[at].right = right;
    return at;
  }

  // Squared distance from p to the node's box (0 inside).
  static double BoxDistance2(const Node& n, Vec2 p) {
    const double dx = std::max({0.0, n.min_x - p.x, p.x - n.max_x});
    const double dy = std::max({0.0, n.min_y - p.y, p.y - n.max_y});
    return dx * dx + dy * dy;
  }

  bool Skip(const Node& n, Vec2 p, double best) const {
    return BoxDistance2(n, p) > best * best * (1.0 + 1e-9);
  }

  void Search(std::size_t at, Vec2 p, std::size_t self, double* best) const {
    const Node& n = nodes_[at];
    // Nothing is nearer than a point at the same place (all at one place: no N^2 walk).
    if (*best == 0.0 || Skip(n, p, *best)) return;
    if (n.left == 0) {
      for (std::size_t k = n.begin; k < n.end; ++k) {
        const std::size_t j = order_[k];
        if (j != self) *best = std::min(*best, Distance(p, points_[j]));
      }
      return;
    }
    std::size_t first = n.left;
    std::size_t second = n.right;
    if (BoxDistance2(nodes_[second], p) < BoxDistance2(nodes_[first], p)) std::swap(first, second);
    Search(first, p, self, best);
    Search(second, p, self, best);
  }

  const std::vector<Vec2>& points_;
  std::vector<std::size_t> order_;
  std::vector<Node> nodes_;
};

}  // namespace

std::vector<double> NearestNeighbourDistances(const std::vector<Vec2>& positions) {
  std::vector<double> nearest(positions.size(), std::numeric_limits<double>::infinity());
  if (positions.size() < 2) return nearest;
  const NearestTree tree(positions);
  for (std::size_t i = 0; i < positions.size(); ++i) nearest[i] = tree.Nearest(i);
  return nearest;
}

SwarmComponents::SwarmComponents(const std::vector<Vec2>& positions, double local_range_m) {
  const std::size_t n = positions.size();
  UnionFind sets(n);
  if (std::isfinite(local_range_m) && local_range_m > 0.0) {
    const double range2 = local_range_m * local_range_m;
    std::unordered_map<std::uint64_t, std::vector<std::size_t>> grid;
    grid.reserve(n);
    std::vector<std::pair<std::int64_t, std::int64_t>> cells(n);
    for (std::size_t i = 0; i < n; ++i) {
      if (!Finite(positions[i])) continue;
      cells[i] = {CellIndex(positions[i].x, local_range_m),
                  CellIndex(positions[i].y, local_range_m)};
      grid[CellKey(cells[i].first, cells[i].second)].push_back(i);
    }
    // Robots within range are in the same or an adjacent cell; each pair is checked from its
    // higher index only.
    for (std::size_t i = 0; i < n; ++i) {
      if (!Finite(positions[i])) continue;
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          const auto it = grid.find(CellKey(cells[i].first + dx, cells[i].second + dy));
          if (it == grid.end()) continue;
          for (std::size_t j : it->second) {
            if (j >= i) continue;
            const double ex = positions[i].x - positions[j].x;
            const double ey = positions[i].y - positions[j].y;
            if (ex * ex + ey * ey <= range2) sets.Union(i, j);
          }
        }
      }
    }
  }
  labels_.assign(n, 0);
  std::unordered_map<std::size_t, std::size_t> label_of_root;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t root = sets.Find(i);
    const auto inserted = label_of_root.emplace(root, sizes_.size());
    if (inserted.second) sizes_.push_back(0);
    labels_[i] = inserted.first->second;
    ++sizes_[labels_[i]];
  }
}

std::size_t SwarmComponents::LargestSwarm() const {
  return sizes_.empty() ? 0 : *std::max_element(sizes_.begin(), sizes_.end());
}

Dispersion DispersionOf(const std::vector<Vec2>& positions, double world_size_m,
                        double cover_radius_m, double cell_m) {
  Dispersion d;
  d.nn_mean_m = std::numeric_limits<double>::quiet_NaN();
  d.nn_cv = d.nn_mean_m;
  std::vector<Vec2> at;
  for (const Vec2& p : positions) {
    if (std::isfinite(p.x) && std::isfinite(p.y)) at.push_back(p);
  }
  if (!(world_size_m > 0.0) || !(cell_m > 0.0) || !std::isfinite(world_size_m)) return d;
  // Every robot marks the cells around it: N x (2 r / cell)^2 tests, not N x cells.
  const long cells = std::max(1L, static_cast<long>(std::ceil(world_size_m / cell_m - 1e-9)));
  std::vector<char> covered(static_cast<std::size_t>(cells * cells), 0);
  const auto cell_of = [&](double v) {
    return std::clamp(static_cast<long>(std::floor(v / cell_m)), 0L, cells - 1);
  };
  for (const Vec2& p : at) {
    for (long i = cell_of(p.x - cover_radius_m); i <= cell_of(p.x + cover_radius_m); ++i) {
      for (long j = cell_of(p.y - cover_radius_m); j <= cell_of(p.y + cover_radius_m); ++j) {
        const Vec2 centre{(i + 0.5) * cell_m, (j + 0.5) * cell_m};
        if (!FartherThan(p, centre, cover_radius_m)) covered[i * cells + j] = 1;
      }
    }
  }
  d.coverage_fraction = static_cast<double>(std::count(covered.begin(), covered.end(), 1)) /
                        static_cast<double>(covered.size());
  if (at.size() < 2) return d;
  const std::vector<double> nearest = NearestNeighbourDistances(at);
  const double mean = Mean(nearest);
  double squares = 0.0;
  for (const double v : nearest) squares += (v - mean) * (v - mean);
  d.nn_mean_m = mean;
  d.nn_cv = mean > 0.0 ? std::sqrt(squares / static_cast<double>(nearest.size())) / mean
                       : std::numeric_limits<double>::quiet_NaN();
  return d;
}

double Mean(const std::vector<double>& values) { return MeanOfRange(values.begin(), values.end()); }

double Median(std::vector<double> values) {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : (values[n / 2 - 1] + values[n / 2]) / 2.0;
}

double TrimmedMean(std::vector<double> values, std::size_t middle) {
  const std::size_t n = values.size();
  if (middle == 0 || middle >= n) return Mean(values);
  std::sort(values.begin(), values.end());
  const std::size_t drop = (n - middle) / 2;
  return MeanOfRange(values.begin() + static_cast<std::ptrdiff_t>(drop),
                     values.end() - static_cast<std::ptrdiff_t>(drop));
}

double TrimmedMean(std::vector<double> values) {
  const std::size_t n = values.size();
  return TrimmedMean(std::move(values), n < 5 ? 0 : n - 4);
}

bool TransportTracker::Feed(std::uint64_t tick, const std::vector<Vec2>& positions,
                            const std::vector<bool>& is_leader) {
  if (positions.empty() || is_leader.size() != positions.size() ||
      !std::all_of(positions.begin(), positions.end(), Finite)) {
    return false;
  }
  if (!started_) {
    started_ = true;
    first_tick_ = last_tick_ = tick;
    previous_ = positions;
    return true;
  }
  if (positions.size() != previous_.size() || tick <= last_tick_) return false;
  const std::size_t n = positions.size();
  Vec2 centroid_delta;
  for (std::size_t i = 0; i < n; ++i) {
    centroid_delta = centroid_delta + (positions[i] - previous_[i]);
  }
  centroid_delta = centroid_delta * (1.0 / static_cast<double>(n));
  // A passive robot's contact looks at the leaders only: O(robots x leaders), not robots^2.
  std::vector<std::size_t> leaders;
  for (std::size_t j = 0; j < n; ++j) {
    if (is_leader[j]) leaders.push_back(j);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const Vec2 delta = positions[i] - previous_[i];
    slip_sum_ += Norm(delta - centroid_delta);
    const double moved = Norm(delta);
    distance_sum_ += moved;
    if (is_leader[i] && moved < kLeaderWaitM) ++leader_waits_;
    if (is_leader[i] || contact_range_m_ <= 0.0) continue;
    ++passive_ticks_;
    for (std::size_t j : leaders) {
      if (!FartherThan(positions[i], positions[j], contact_range_m_)) {
        ++contact_ticks_;
        break;
      }
    }
  }
  previous_ = positions;
  last_tick_ = tick;
  return true;
}

double TransportTracker::SlipPerRobot() const {
  return previous_.empty() ? 0.0 : slip_sum_ / static_cast<double>(previous_.size());
}

double TransportTracker::DistancePerRobot() const {
  return previous_.empty() ? 0.0 : distance_sum_ / static_cast<double>(previous_.size());
}

std::optional<double> TransportTracker::LeaderContact() const {
  if (passive_ticks_ == 0) return std::nullopt;
  return static_cast<double>(contact_ticks_) / static_cast<double>(passive_ticks_);
}

LeaderTracker::LeaderTracker(Vec2 target, double local_range_m)
    : target_(target), local_range_m_(local_range_m) {}

bool LeaderTracker::Feed(std::uint64_t tick, const std::vector<Vec2>& positions,
                         std::size_t leader) {
  if (leader >= positions.size() || !Finite(positions[leader])) return false;
  if (started_ && tick <= last_tick_) return false;
  const Vec2 self = positions[leader];
  if (!started_) {
    started_ = true;
    first_tick_ = tick;
    start_ = self;
  } else if (Norm(self - previous_) < kLeaderWaitM) {
    ++waits_;
  }
  last_tick_ = tick;
  previous_ = self;
  distance_to_target_ = Distance(self, target_);
  const SwarmComponents swarms(positions, local_range_m_);
  const std::size_t attached = swarms.SizeOfSwarmOf(leader);
  swarm_at_last_ = attached - 1;
  if (!lost_ && attached < positions.size()) {
    lost_ = true;
    const double start_distance = Distance(start_, target_);
    path_fraction_ = start_distance > 0.0
                         ? std::clamp(1.0 - distance_to_target_ / start_distance, 0.0, 1.0)
                         : 1.0;
  }
  return true;
}

}  // namespace core
}  // namespace swarm_transport
