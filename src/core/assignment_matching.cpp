#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "swarm_transport/core/assignment.h"

// The assignments of a cost matrix: the paper's greedy global minimum, its naive row minimum,
// the optimal ones (Hungarian, bottleneck) [R3, SPEC 9.10].

namespace swarm_transport {
namespace core {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Matching Score(const CostMatrix& m, std::vector<int> target_of) {
  Matching out;
  out.target_of = std::move(target_of);
  for (std::size_t r = 0; r < m.rows; ++r) {
    if (out.target_of[r] < 0) continue;
    const double c = m.at(r, static_cast<std::size_t>(out.target_of[r]));
    out.total += c;
    out.last = std::max(out.last, c);
  }
  return out;
}

CostMatrix Transposed(const CostMatrix& m) {
  CostMatrix t(m.cols, m.rows);
  for (std::size_t r = 0; r < m.rows; ++r) {
    for (std::size_t c = 0; c < m.cols; ++c) t.at(c, r) = m.at(r, c);
  }
  return t;
}

// Hungarian method with potentials for rows <= cols: the column of each row.
std::vector<int> HungarianWide(const CostMatrix& a) {
  const std::size_t n = a.rows;
  const std::size_t m = a.cols;
  std::vector<double> u(n + 1, 0.0), v(m + 1, 0.0);
  std::vector<std::size_t> p(m + 1, 0), way(m + 1, 0);
  for (std::size_t i = 1; i <= n; ++i) {
    p[0] = i;
    std::size_t j0 = 0;
    std::vector<double> minv(m + 1, kInf);
    std::vector<bool> used(m + 1, false);
    do {
      used[j0] = true;
      const std::size_t i0 = p[j0];
      double delta = kInf;
      std::size_t j1 = 0;
      for (std::size_t j = 1; j <= m; ++j) {
        if (used[j]) continue;
        const double cur = a.at(i0 - 1, j - 1) - u[i0] - v[j];
        if (cur < minv[j]) {
          minv[j] = cur;
          way[j] = j0;
        }
        if (minv[j] < delta) {
          delta = minv[j];
          j1 = j;
        }
      }
      for (std::size_t j = 0; j <= m; ++j) {
        if (used[j]) {
          u[p[j]] += delta;
          v[j] -= delta;
        } else {
          minv[j] -= delta;
        }
      }
      j0 = j1;
    } while (p[j0] != 0);
    do {
      const std::size_t j1 = way[j0];
      p[j0] = p[j1];
      j0 = j1;
    } while (j0 != 0);
  }
  std::vector<int> col_of(n, -1);
  for (std::size_t j = 1; j <= m; ++j) {
    if (p[j] != 0) col_of[p[j] - 1] = static_cast<int>(j - 1);
  }
  return col_of;
}

std::vector<int> HungarianAny(const CostMatrix& m) {
  if (m.rows <= m.cols) return HungarianWide(m);
  const std::vector<int> row_of = HungarianWide(Transposed(m));
  std::vector<int> col_of(m.rows, -1);
  for (std::size_t c = 0; c < row_of.size(); ++c) {
    if (row_of[c] >= 0) col_of[static_cast<std::size_t>(row_of[c])] = static_cast<int>(c);
  }
  return col_of;
}

// Kuhn's augmenting path from row r over the edges allowed by `ok`.
bool Augment(const CostMatrix& m, double limit, std::size_t r, std::vector<bool>* seen,
             std::vector<int>* row_of_col) {
  for (std::size_t c = 0; c < m.cols; ++c) {
    if (m.at(r, c) > limit || (*seen)[c]) continue;
    (*seen)[c] = true;
    const int owner = (*row_of_col)[c];
    if (owner < 0 || Augment(m, limit, static_cast<std::size_t>(owner), seen, row_of_col)) {
      (*row_of_col)[c] = static_cast<int>(r);
      return true;
    }
  }
  return false;
}

// Largest matching using only costs <= limit.
std::size_t MatchingSize(const CostMatrix& m, double limit) {
  std::vector<int> row_of_col(m.cols, -1);
  std::size_t size = 0;
  for (std::size_t r = 0; r < m.rows; ++r) {
    std::vector<bool> seen(m.cols, false);
    if (Augment(m, limit, r, &seen, &row_of_col)) ++size;
  }
  return size;
}

}  // namespace

std::string ValidateCostMatrix(const CostMatrix& m) {
  if (m.cost.size() != m.rows * m.cols) {
    std::ostringstream os;
    os << "cost matrix has " << m.cost.size() << " entries for " << m.rows << " x " << m.cols;
    return os.str();
  }
  for (double c : m.cost) {
    if (!std::isfinite(c)) return "cost matrix entries must be finite";
  }
  return "";
}

Matching GreedyMinimum(const CostMatrix& m) { return GreedyMinimumAfter(m, {}, nullptr); }

Matching GreedyMinimumAfter(const CostMatrix& m, const std::vector<Pick>& fixed,
                            std::vector<Pick>* order) {
  std::vector<int> target_of(m.rows, -1);
  std::vector<bool> row_used(m.rows, false), col_used(m.cols, false);
  if (order) order->clear();
  std::size_t picks = std::min(m.rows, m.cols);
  for (const Pick& f : fixed) {
    if (f.row >= m.rows || f.col >= m.cols || row_used[f.row] || col_used[f.col]) continue;
    row_used[f.row] = true;
    col_used[f.col] = true;
    target_of[f.row] = static_cast<int>(f.col);
    if (order) order->push_back(f);
    --picks;
  }
  for (std::size_t k = 0; k < picks; ++k) {
    // The first free pair stands until a smaller cost is found (so that a matrix of
    // infinities still gives one robot per target).
    bool found = false;
    double best = kInf;
    std::size_t br = 0, bc = 0;
    for (std::size_t r = 0; r < m.rows; ++r) {
      if (row_used[r]) continue;
      for (std::size_t c = 0; c < m.cols; ++c) {
        if (col_used[c]) continue;
        if (!found || m.at(r, c) < best) {
          found = true;
          best = m.at(r, c);
          br = r;
          bc = c;
        }
      }
    }
    row_used[br] = true;
    col_used[bc] = true;
    target_of[br] = static_cast<int>(bc);
    if (order) order->push_back({br, bc});
  }
  return Score(m, target_of);
}

Matching RowMinimum(const CostMatrix& m) {
  std::vector<int> target_of(m.rows, -1);
  for (std::size_t r = 0; r < m.rows && m.cols > 0; ++r) {
    std::size_t best = 0;
    for (std::size_t c = 1; c < m.cols; ++c) {
      if (m.at(r, c) < m.at(r, best)) best = c;
    }
    target_of[r] = static_cast<int>(best);
  }
  return Score(m, target_of);
}

Matching Hungarian(const CostMatrix& m) {
  if (m.rows == 0 || m.cols == 0) return Score(m, std::vector<int>(m.rows, -1));
  return Score(m, HungarianAny(m));
}

Matching Bottleneck(const CostMatrix& m) {
  if (m.rows == 0 || m.cols == 0) return Score(m, std::vector<int>(m.rows, -1));
  std::vector<double> levels = m.cost;
  std::sort(levels.begin(), levels.end());
  levels.erase(std::unique(levels.begin(), levels.end()), levels.end());
  const std::size_t full = std::min(m.rows, m.cols);
  std::size_t lo = 0, hi = levels.size() - 1;  // the largest level always allows a full matching
  while (lo < hi) {
    const std::size_t mid = (lo + hi) / 2;
    if (MatchingSize(m, levels[mid]) == full) {
      hi = mid;
    } else {
      lo = mid + 1;
    }
  }
  const double limit = levels[lo];
  // Least total among the matchings within the limit: every cost above it made prohibitive
  // (more than any sum of allowed costs can reach).
  double span = 0.0;
  for (double c : m.cost) span = std::max(span, std::fabs(c));
  const double prohibitive = (span + 1.0) * static_cast<double>(full + 1) * 4.0;
  CostMatrix bounded = m;
  for (double& c : bounded.cost) {
    if (c > limit) c = prohibitive;
  }
  return Score(m, HungarianAny(bounded));
}

}  // namespace core
}  // namespace swarm_transport
