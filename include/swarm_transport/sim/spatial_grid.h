// A uniform grid over points of the arena for "who is within d of whom" (the radio's range, the
// robots' contacts). Only an accelerator: its callers check every distance themselves and sort
// what they found, so their results never depend on the grid.
#ifndef SWARM_TRANSPORT_SIM_SPATIAL_GRID_H_
#define SWARM_TRANSPORT_SIM_SPATIAL_GRID_H_

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "swarm_transport/core/geometry.h"

namespace swarm_transport {
namespace sim {

// Cells of the search distance itself (however big the arena), the points stored in compressed
// rows by cell. When the arena has at most a few cells per point (the radio's range at any
// density a flock spreads to) the cells are a dense table, so that the 3x3 cells around a
// point are three contiguous runs; else (a robot's contact distance in a large arena) the cells
// are hashed into about twice as many buckets as points, a row's cells into consecutive
// buckets from a hashed start (so that the 3x3 cells are three runs there too), and a bucket
// may also hold points of other cells (the callers' distance checks drop them). Memory and set-up
// are O(points) either way. Until 2026-11-25 the cells were at least arena / sqrt(N) wide, so that
// a flock crowded into a few cells made every search scan the whole crowd (at 2,000 robots the
// push-apart search was 18 % of a real-time host_sim process).
class SpatialGrid {
 public:
  // Sorts `points` (kept by reference until the next Build) into cells of `cell_m`; the
  // grid's memory is kept from one Build to the next.
  void Build(const std::vector<core::Vec2>& points, double world_size_m, double cell_m);

  // Calls f(j) once for every point j in the cells (or their buckets) of the 3x3 cells around
  // point i (j may equal i). Every point within cell_m of point i is among them.
  template <typename F>
  void ForNearby(std::size_t i, F f) const {
    ForNear((*points_)[i], f);
  }
  // The same around any position `p`: every point within cell_m of `p` is among them. A point
  // counts where it was at the Build (a point that moved since may be missed, or found far).
  template <typename F>
  void ForNear(core::Vec2 p, F f) const {
    const int cx = CellOf(p.x);
    const int cy = CellOf(p.y);
    const int x0 = std::max(0, cx - 1);
    const int x1 = std::min(side_ - 1, cx + 1);
    const int y0 = std::max(0, cy - 1);
    const int y1 = std::min(side_ - 1, cy + 1);
    if (dense_) {
      for (int y = y0; y <= y1; ++y) {
        const std::size_t row = static_cast<std::size_t>(y) * static_cast<std::size_t>(side_);
        const std::uint32_t end = start_[row + static_cast<std::size_t>(x1) + 1];
        for (std::uint32_t k = start_[row + static_cast<std::size_t>(x0)]; k < end; ++k) {
          f(static_cast<std::size_t>(order_[k]));
        }
      }
      return;
    }
    // A row's cells are consecutive buckets: three runs of the table unless two rows' runs
    // share a bucket or one wraps round the table's end (then bucket by bucket, each once).
    const std::uint32_t width = static_cast<std::uint32_t>(x1 - x0 + 1);
    std::uint32_t first[3];
    int rows = 0;
    bool runs = true;
    for (int y = y0; y <= y1; ++y) {
      const std::uint32_t b = Bucket(x0, y);
      if (b + width - 1 > mask_) runs = false;
      for (int r = 0; r < rows; ++r) {
        if (b < first[r] + width && first[r] < b + width) runs = false;
      }
      first[rows++] = b;
    }
    if (runs) {
      for (int r = 0; r < rows; ++r) {
        const std::uint32_t end = start_[first[r] + width];
        for (std::uint32_t k = start_[first[r]]; k < end; ++k) {
          f(static_cast<std::size_t>(order_[k]));
        }
      }
      return;
    }
    std::uint32_t seen[9];
    int n_seen = 0;
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const std::uint32_t b = Bucket(x, y);
        // Two of the nine cells in one bucket: its points once.
        bool again = false;
        for (int k = 0; k < n_seen; ++k) again = again || seen[k] == b;
        if (again) continue;
        seen[n_seen++] = b;
        for (std::uint32_t k = start_[b]; k < start_[b + 1]; ++k) {
          f(static_cast<std::size_t>(order_[k]));
        }
      }
    }
  }

 private:
  int CellOf(double v) const {
    const int c = static_cast<int>(std::floor(v / cell_m_));
    return std::min(side_ - 1, std::max(0, c));
  }
  // A row's cells in consecutive buckets from a hashed start.
  std::uint32_t Bucket(int x, int y) const {
    const std::uint64_t h =
        static_cast<std::uint64_t>(static_cast<std::uint32_t>(y)) * 0xC2B2AE3D27D4EB4FULL;
    return static_cast<std::uint32_t>(((h ^ (h >> 29)) + static_cast<std::uint32_t>(x)) & mask_);
  }
  // The cell (dense) or bucket (hashed) of a point.
  std::uint32_t Slot(core::Vec2 p) const;

  const std::vector<core::Vec2>* points_ = nullptr;
  double cell_m_ = 1.0;
  int side_ = 1;
  bool dense_ = false;
  std::uint64_t mask_ = 0;
  std::vector<std::uint32_t> start_;  // slots + 1 entries
  std::vector<std::uint32_t> order_;  // point indices by slot
  std::vector<std::uint32_t> slot_of_;
};

}  // namespace sim
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_SIM_SPATIAL_GRID_H_
