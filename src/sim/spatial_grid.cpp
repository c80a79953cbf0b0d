#include "swarm_transport/sim/spatial_grid.h"

namespace swarm_transport {
namespace sim {
namespace {

// The grid's cells are at least arena / this wide (a zero or tiny search distance stays finite).
constexpr double kMaxCellsPerSide = 1.0e6;
// A dense table when it has at most this many cells per point (plus a few for small swarms).
constexpr std::uint64_t kDenseCellsPerPoint = 8;
constexpr std::uint64_t kDenseCellsExtra = 64;

}  // namespace

std::uint32_t SpatialGrid::Slot(core::Vec2 p) const {
  const int x = CellOf(p.x);
  const int y = CellOf(p.y);
  if (dense_) return static_cast<std::uint32_t>(y * side_ + x);
  return Bucket(x, y);
}

void SpatialGrid::Build(const std::vector<core::Vec2>& points, double world_size_m, double cell_m) {
  points_ = &points;
  cell_m_ = std::max(cell_m, world_size_m / kMaxCellsPerSide);
  side_ = std::max(1, static_cast<int>(std::ceil(world_size_m / cell_m_)));
  const std::uint64_t cells = static_cast<std::uint64_t>(side_) * static_cast<std::uint64_t>(side_);
  dense_ = cells <= kDenseCellsPerPoint * points.size() + kDenseCellsExtra;
  std::size_t slots = 0;
  if (dense_) {
    slots = static_cast<std::size_t>(cells);
  } else {
    slots = 16;
    while (slots < 2 * points.size()) slots *= 2;
    mask_ = slots - 1;
  }
  start_.assign(slots + 1, 0);
  slot_of_.resize(points.size());
  for (std::size_t i = 0; i < points.size(); ++i) {
    slot_of_[i] = Slot(points[i]);
    ++start_[slot_of_[i] + 1];
  }
  for (std::size_t b = 1; b < start_.size(); ++b) start_[b] += start_[b - 1];
  order_.resize(points.size());
  // Points in ascending index within a slot; start_[b] runs to the end of slot b, then every
  // entry moves up by one to be the start of its slot again.
  for (std::size_t i = 0; i < points.size(); ++i)
    order_[start_[slot_of_[i]]++] = static_cast<std::uint32_t>(i);
  for (std::size_t b = slots; b > 0; --b) start_[b] = start_[b - 1];
  start_[0] = 0;
}

}  // namespace sim
}  // namespace swarm_transport
