// World2D's searches over the robots' positions: contacts pushed apart and neighbour tables.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <utility>

#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace sim {
namespace {

// Centres closer than this are coincident: they separate along x (by id order).
constexpr double kCoincidentM = 1e-12;
// Push-apart passes per Step (each pass resolves every overlapping pair once).
constexpr int kPushIterations = 5;

using core::SquaredDistance;

}  // namespace

void World2D::ResolveContacts() {
  if (!params_.push_apart) return;
  std::vector<Robot*>& order = push_order_;
  std::vector<core::Vec2>& points = push_points_;
  order.clear();
  points.clear();
  for (auto& entry : robots_) {
    order.push_back(&entry.second);
    points.push_back(entry.second.pose.position);
  }
  std::vector<std::uint8_t>& touched = push_touched_;
  touched.clear();  // the first pass searches around every robot
  for (int i = 0; i < kPushIterations; ++i) {
    const bool pushed = PushApartOnce(&touched);
    // ClampAll, remembering whom the wall moved: the next pass searches around them too.
    for (std::size_t k = 0; k < order.size(); ++k) {
      core::Vec2& p = order[k]->pose.position;
      const core::Vec2 clamped = Clamped(p);
      if (clamped.x != p.x || clamped.y != p.y) {
        p = clamped;
        touched[k] = 1;
      }
      if (touched[k]) points[k] = p;  // the others did not move
    }
    if (!pushed) break;
  }
}

void World2D::ClampAll() {
  for (auto& entry : robots_) entry.second.pose.position = Clamped(entry.second.pose.position);
}

void World2D::BuildContactGrid() {
  push_grid_.Build(push_points_, params_.world_size_m, 2.0 * params_.robot_radius_m);
  push_moved_.assign(push_points_.size(), 0);
  push_moved_list_.clear();
}

bool World2D::PushApartOnce(std::vector<std::uint8_t>* touched) {
  const std::vector<Robot*>& order = push_order_;
  const std::vector<core::Vec2>& points = push_points_;
  std::vector<std::pair<std::size_t, std::size_t>>& pairs = push_pairs_;
  const double contact = 2.0 * params_.robot_radius_m;
  const double contact2 = contact * contact;
  const auto add = [&](std::size_t i, std::size_t j) {
    if (SquaredDistance(points[i], points[j]) < contact2) {
      pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
  };
  if (touched->empty()) {
    // Around every robot, each pair once (from its lower robot).
    pairs.clear();
    BuildContactGrid();
    for (std::size_t i = 0; i < points.size(); ++i) {
      push_grid_.ForNearby(i, [&](std::size_t j) {
        if (j > i) add(i, j);
      });
    }
  } else {
    // The last pass's pairs of two robots that did not move since: still as close (a pair
    // whose squared distance is below the contact's but whose distance, rounded, is not was
    // left alone, and a push of one of them later in a pass would have used it).
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                               [&](const std::pair<std::size_t, std::size_t>& p) {
                                 return (*touched)[p.first] != 0 || (*touched)[p.second] != 0;
                               }),
                pairs.end());
    // Around the robots moved by the last pass, each pair once (from its lower robot when both
    // moved). The grid holds every robot where it was at its build: the robots moved since are
    // searched in a grid of their own (rebuilt each pass: a few), the others in the big one
    // (rebuilt only when many moved).
    for (std::size_t k = 0; k < points.size(); ++k) {
      if ((*touched)[k] != 0 && push_moved_[k] == 0) {
        push_moved_[k] = 1;
        push_moved_list_.push_back(k);
      }
    }
    if (push_moved_list_.size() > points.size() / 8) BuildContactGrid();
    push_moved_points_.clear();
    for (std::size_t k : push_moved_list_) push_moved_points_.push_back(points[k]);
    push_moved_grid_.Build(push_moved_points_, params_.world_size_m, contact);
    for (std::size_t i = 0; i < points.size(); ++i) {
      if ((*touched)[i] == 0) continue;
      push_grid_.ForNear(points[i], [&](std::size_t j) {
        // The robots moved since the build are the other grid's (after a rebuild: none).
        if (push_moved_[j] != 0 || j == i || (j < i && (*touched)[j] != 0)) return;
        add(i, j);
      });
      push_moved_grid_.ForNear(points[i], [&](std::size_t m) {
        const std::size_t j = push_moved_list_[m];
        if (j == i || (j < i && (*touched)[j] != 0)) return;
        add(i, j);
      });
    }
  }
  touched->assign(points.size(), 0);
  if (pairs.empty()) return false;
  // Pairs in id order (the robots are sorted by id): the result never depends on the grid.
  std::sort(pairs.begin(), pairs.end());
  bool pushed = false;
  for (const auto& pair : pairs) {
    core::Vec2& a = order[pair.first]->pose.position;
    core::Vec2& b = order[pair.second]->pose.position;
    const double dx = b.x - a.x;
    const double dy = b.y - a.y;
    const double d = std::sqrt(dx * dx + dy * dy);
    if (d >= contact) continue;  // an earlier push in this pass already separated them
    double ux = 1.0;             // coincident: the lower id goes to -x, the higher to +x
    double uy = 0.0;
    if (d > kCoincidentM) {
      ux = dx / d;
      uy = dy / d;
    }
    const double half = 0.5 * (contact - d);
    a.x -= ux * half;
    a.y -= uy * half;
    b.x += ux * half;
    b.y += uy * half;
    (*touched)[pair.first] = 1;
    (*touched)[pair.second] = 1;
    pushed = true;
  }
  return pushed;
}

std::vector<std::vector<std::uint16_t>> World2D::NeighbourLists(double range_m) const {
  NeighbourTable table;
  NeighbourIndices(range_m, &table);
  std::vector<std::uint16_t> ids;
  ids.reserve(robots_.size());
  for (const auto& entry : robots_) ids.push_back(entry.first);
  std::vector<std::vector<std::uint16_t>> lists(robots_.size());
  for (std::size_t i = 0; i < lists.size(); ++i) {
    for (std::uint32_t k = table.start[i]; k < table.start[i + 1]; ++k) {
      lists[i].push_back(ids[table.index[k]]);
    }
  }
  return lists;
}

void World2D::NeighbourIndices(double range_m, NeighbourTable* out) const {
  const std::size_t n = robots_.size();
  out->start.assign(n + 1, 0);
  out->index.clear();
  if (!(range_m > 0.0) || !std::isfinite(range_m)) return;
  std::vector<core::Vec2>& points = out->points;
  points.clear();
  points.reserve(n);
  for (const auto& entry : robots_) points.push_back(entry.second.pose.position);
  SpatialGrid& grid = out->grid;
  grid.Build(points, params_.world_size_m, range_m);
  const double range2 = range_m * range_m;
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t first = out->index.size();
    grid.ForNearby(i, [&](std::size_t j) {
      if (j != i && SquaredDistance(points[i], points[j]) <= range2) {
        out->index.push_back(static_cast<std::uint32_t>(j));
      }
    });
    std::sort(out->index.begin() + static_cast<std::ptrdiff_t>(first), out->index.end());
    out->start[i + 1] = static_cast<std::uint32_t>(out->index.size());
  }
}

}  // namespace sim
}  // namespace swarm_transport
