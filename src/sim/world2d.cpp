#include "swarm_transport/sim/world2d.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <utility>

#include "swarm_transport/core/random.h"

namespace swarm_transport {
namespace sim {
namespace {

// A command with less than this left is over (sums of sub-steps leave ~1e-17 s crumbs).
constexpr double kTimeEpsilonS = 1e-9;
// Positions on the arena border count as inside when rounding put them this far out.
constexpr double kInsideToleranceM = 1e-9;
// Centres closer than this are coincident: they separate along x (by id order).
constexpr double kCoincidentM = 1e-12;
// Push-apart passes per Step (each pass resolves every overlapping pair once).
constexpr int kPushIterations = 5;
// The grid's cells are at least arena / this wide (a zero or tiny search distance stays finite).
constexpr double kMaxCellsPerSide = 1.0e6;
// Random placement keeps centres this many times the separation apart [thesis 10% margin,
// times 1.5 so that robots start with room to move].
constexpr double kPlacementMargin = 1.1 * 1.5;
// Random placement gives up after this many rejected tries for one robot.
constexpr int kPlacementAttempts = 5000;
// Stream of the placement generator ("place"); robots use their id (< 65536) as stream.
constexpr std::uint64_t kPlacementStream = 0x706c616365ULL;
// Corner placement: grid spacing in radii, and the heading of every robot.
constexpr double kCornerSpacingRadii = 3.0;
constexpr double kCornerHeadingDeg = 45.0;

using core::SquaredDistance;

void SetError(std::string* error, const std::string& text) {
  if (error != nullptr) *error = text;
}

// A hashed uniform grid: cells of `cell_m` (the search distance itself, however big the
// arena), hashed into about twice as many buckets as points and stored in compressed rows (the
// points of bucket b are order_[start_[b] .. start_[b + 1]), ascending). Memory and set-up are
// O(points) for any arena and cell size; a bucket may also hold points of other cells, which
// the callers' distance checks drop. Until 2026-11-25 the cells were at least arena / sqrt(N)
// wide, so that a flock crowded into a few cells made every search scan the whole crowd (at
// 2,000 robots the push-apart search was 18 % of a real-time host_sim process).
class Grid {
 public:
  Grid(const std::vector<core::Vec2>& points, double world_size_m, double cell_m)
      : points_(points),
        cell_m_(std::max(cell_m, world_size_m / kMaxCellsPerSide)),
        side_(std::max(1, static_cast<int>(std::ceil(world_size_m / cell_m_)))) {
    std::size_t buckets = 16;
    while (buckets < 2 * points.size()) buckets *= 2;
    mask_ = buckets - 1;
    std::vector<int> count(buckets + 1, 0);
    std::vector<std::uint32_t> bucket_of(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      bucket_of[i] = Bucket(CellX(points[i].x), CellX(points[i].y));
      ++count[bucket_of[i] + 1];
    }
    for (std::size_t b = 1; b < count.size(); ++b) count[b] += count[b - 1];
    start_ = count;
    order_.resize(points.size());
    for (std::size_t i = 0; i < points.size(); ++i) {
      order_[static_cast<std::size_t>(count[bucket_of[i]]++)] = static_cast<int>(i);
    }
  }

  // Calls f(j) once for every point j in the buckets of the 3x3 cells around point i (j may
  // equal i). Every point within cell_m of point i is among them.
  template <typename F>
  void ForNearby(std::size_t i, F f) const {
    const int cx = CellX(points_[i].x);
    const int cy = CellX(points_[i].y);
    std::uint32_t seen[9];
    int n_seen = 0;
    for (int y = std::max(0, cy - 1); y <= std::min(side_ - 1, cy + 1); ++y) {
      for (int x = std::max(0, cx - 1); x <= std::min(side_ - 1, cx + 1); ++x) {
        const std::uint32_t b = Bucket(x, y);
        // Two of the nine cells in one bucket: its points once.
        if (std::find(seen, seen + n_seen, b) != seen + n_seen) continue;
        seen[n_seen++] = b;
        for (int k = start_[b]; k < start_[b + 1]; ++k) {
          f(static_cast<std::size_t>(order_[static_cast<std::size_t>(k)]));
        }
      }
    }
  }

 private:
  int CellX(double v) const {
    const int c = static_cast<int>(std::floor(v / cell_m_));
    return std::min(side_ - 1, std::max(0, c));
  }
  std::uint32_t Bucket(int x, int y) const {
    const std::uint64_t h =
        (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) * 0x9E3779B97F4A7C15ULL) ^
        (static_cast<std::uint64_t>(static_cast<std::uint32_t>(y)) * 0xC2B2AE3D27D4EB4FULL);
    return static_cast<std::uint32_t>((h ^ (h >> 29)) & mask_);
  }

  const std::vector<core::Vec2>& points_;
  double cell_m_;
  int side_;
  std::uint64_t mask_ = 0;
  std::vector<int> start_;
  std::vector<int> order_;
};

bool IsFinite(const core::Pose2& pose) {
  return std::isfinite(pose.position.x) && std::isfinite(pose.position.y) &&
         std::isfinite(pose.heading.degrees());
}

}  // namespace

std::string WorldParams::Validate() const {
  std::ostringstream os;
  if (!std::isfinite(world_size_m) || !(world_size_m > 0.0)) {
    os << "world_size_m must be > 0 but is " << world_size_m;
  } else if (!std::isfinite(robot_radius_m) || !(robot_radius_m > 0.0) ||
             !(2.0 * robot_radius_m < world_size_m)) {
    os << "robot_radius_m must be in (0, world_size_m / 2) but is " << robot_radius_m;
  } else if (!std::isfinite(integration_step_s) || !(integration_step_s > 0.0)) {
    os << "integration_step_s must be > 0 but is " << integration_step_s;
  } else if (!std::isfinite(command_duration_s) || !(command_duration_s > 0.0)) {
    os << "command_duration_s must be > 0 but is " << command_duration_s;
  }
  return os.str();
}

World2D::World2D(const WorldParams& params) : params_(params) {}

bool World2D::Inside(const core::Pose2& pose, std::string* error) const {
  if (!IsFinite(pose)) {
    SetError(error, "the pose must be finite");
    return false;
  }
  const double lo = params_.robot_radius_m - kInsideToleranceM;
  const double hi = params_.world_size_m - params_.robot_radius_m + kInsideToleranceM;
  const core::Vec2 p = pose.position;
  if (p.x < lo || p.x > hi || p.y < lo || p.y > hi) {
    std::ostringstream os;
    os << "(" << p.x << ", " << p.y << ") is outside the arena: x and y must be in ["
       << params_.robot_radius_m << ", " << params_.world_size_m - params_.robot_radius_m << "]";
    SetError(error, os.str());
    return false;
  }
  return true;
}

core::Vec2 World2D::Clamped(core::Vec2 p) const {
  const double lo = params_.robot_radius_m;
  const double hi = params_.world_size_m - params_.robot_radius_m;
  return {std::min(hi, std::max(lo, p.x)), std::min(hi, std::max(lo, p.y))};
}

bool World2D::Spawn(std::uint16_t id, const core::Pose2& pose, std::string* error) {
  if (robots_.count(id) != 0) {
    SetError(error, "robot " + std::to_string(id) + " already exists");
    return false;
  }
  if (!Inside(pose, error)) return false;
  Robot robot;
  robot.id = id;
  robot.pose = pose;
  robot.pose.position = Clamped(pose.position);
  robot.spawn_pose = robot.pose;
  robots_.emplace(id, robot);
  return true;
}

bool World2D::Kill(std::uint16_t id, std::string* error) {
  if (robots_.erase(id) == 0) {
    SetError(error, "robot " + std::to_string(id) + " does not exist");
    return false;
  }
  return true;
}

bool World2D::TeleportAbsolute(std::uint16_t id, const core::Pose2& pose, std::string* error) {
  auto it = robots_.find(id);
  if (it == robots_.end()) {
    SetError(error, "robot " + std::to_string(id) + " does not exist");
    return false;
  }
  if (!Inside(pose, error)) return false;
  it->second.pose = pose;
  it->second.pose.position = Clamped(pose.position);
  return true;
}

bool World2D::TeleportRelative(std::uint16_t id, double linear_m, double angular_rad,
                               std::string* error) {
  auto it = robots_.find(id);
  if (it == robots_.end()) {
    SetError(error, "robot " + std::to_string(id) + " does not exist");
    return false;
  }
  if (!std::isfinite(linear_m) || !std::isfinite(angular_rad)) {
    SetError(error, "linear and angular must be finite");
    return false;
  }
  core::Pose2& pose = it->second.pose;
  pose.heading = pose.heading + core::Angle::FromRadians(angular_rad);
  const double theta = pose.heading.radians();
  pose.position = Clamped(
      {pose.position.x + linear_m * std::cos(theta), pose.position.y + linear_m * std::sin(theta)});
  return true;
}

bool World2D::SetCommand(std::uint16_t id, core::Velocity velocity, std::string* error) {
  auto it = robots_.find(id);
  if (it == robots_.end()) {
    SetError(error, "robot " + std::to_string(id) + " does not exist");
    return false;
  }
  if (!std::isfinite(velocity.linear) || !std::isfinite(velocity.angular)) {
    SetError(error, "the velocity must be finite");
    return false;
  }
  // Turn in place at once, then drive straight for the command's duration: the thesis's tick
  // (teleport_relative, then 1 s of driving) and exactly what core::TurnThenDrive predicts.
  it->second.pose.heading = it->second.pose.heading +
                            core::Angle::FromRadians(velocity.angular * params_.command_duration_s);
  it->second.command = core::Velocity{velocity.linear, 0.0};
  it->second.command_remaining_s = params_.command_duration_s;
  return true;
}

void World2D::Step(double dt_s, bool resolve_contacts) {
  if (!std::isfinite(dt_s) || dt_s < 0.0) return;
  if (dt_s > 0.0) {
    const int substeps =
        std::max(1, static_cast<int>(std::ceil(dt_s / params_.integration_step_s - 1e-9)));
    const double h = dt_s / substeps;
    for (auto& entry : robots_) {
      Robot& robot = entry.second;
      for (int s = 0; s < substeps; ++s) {
        if (robot.command_remaining_s <= 0.0) {
          robot.last_velocity = core::Velocity();
          continue;
        }
        // The last piece of a command is exactly what is left of it, so a command drives for
        // exactly command_duration_s and a robot's prediction matches the simulation.
        const double d = robot.command_remaining_s <= h ? robot.command_remaining_s : h;
        robot.pose = core::Integrate(robot.pose, robot.command, d, &robot.trig);
        robot.last_velocity = robot.command;
        robot.command_remaining_s -= d;
        if (robot.command_remaining_s <= kTimeEpsilonS) {
          robot.command_remaining_s = 0.0;
          robot.command = core::Velocity();
        }
      }
      robot.pose.position = Clamped(robot.pose.position);  // ClampAll in the same pass
    }
  } else {
    ClampAll();
  }
  if (resolve_contacts) ResolveContacts();
}

void World2D::ResolveContacts() {
  if (!params_.push_apart) return;
  std::vector<std::uint8_t>& touched = push_touched_;
  touched.clear();  // the first pass searches around every robot
  for (int i = 0; i < kPushIterations; ++i) {
    const bool pushed = PushApartOnce(&touched);
    // ClampAll, remembering whom the wall moved: the next pass searches around them too.
    std::size_t k = 0;
    for (auto& entry : robots_) {
      core::Vec2& p = entry.second.pose.position;
      const core::Vec2 clamped = Clamped(p);
      if (clamped.x != p.x || clamped.y != p.y) {
        p = clamped;
        touched[k] = 1;
      }
      ++k;
    }
    if (!pushed) break;
  }
}

void World2D::ClampAll() {
  for (auto& entry : robots_) entry.second.pose.position = Clamped(entry.second.pose.position);
}

bool World2D::PushApartOnce(std::vector<std::uint8_t>* touched) {
  std::vector<Robot*>& order = push_order_;
  std::vector<core::Vec2>& points = push_points_;
  std::vector<std::pair<std::size_t, std::size_t>>& pairs = push_pairs_;
  order.clear();
  points.clear();
  const bool all = touched->empty();
  if (all) {
    pairs.clear();
  } else {
    // The last pass's pairs of two robots that did not move since: still as close (a pair
    // whose squared distance is below the contact's but whose distance, rounded, is not was
    // left alone, and a push of one of them later in a pass would have used it).
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                               [&](const std::pair<std::size_t, std::size_t>& p) {
                                 return (*touched)[p.first] != 0 || (*touched)[p.second] != 0;
                               }),
                pairs.end());
  }
  for (auto& entry : robots_) {
    order.push_back(&entry.second);
    points.push_back(entry.second.pose.position);
  }
  const double contact = 2.0 * params_.robot_radius_m;
  const double contact2 = contact * contact;
  {
    const Grid grid(points, params_.world_size_m, contact);
    const auto searched = [&](std::size_t i) { return all || (*touched)[i] != 0; };
    for (std::size_t i = 0; i < points.size(); ++i) {
      if (!searched(i)) continue;
      grid.ForNearby(i, [&](std::size_t j) {
        // Each pair once: from its lower robot when both are searched around.
        if (j == i || (j < i && searched(j))) return;
        if (SquaredDistance(points[i], points[j]) < contact2) {
          pairs.emplace_back(std::min(i, j), std::max(i, j));
        }
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

void World2D::Reset() {
  for (auto& entry : robots_) {
    Robot& robot = entry.second;
    robot.pose = robot.spawn_pose;
    robot.command = core::Velocity();
    robot.command_remaining_s = 0.0;
    robot.last_velocity = core::Velocity();
  }
}

const Robot* World2D::Find(std::uint16_t id) const {
  auto it = robots_.find(id);
  return it == robots_.end() ? nullptr : &it->second;
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
  std::vector<core::Vec2> points;
  points.reserve(n);
  for (const auto& entry : robots_) points.push_back(entry.second.pose.position);
  const Grid grid(points, params_.world_size_m, range_m);
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

bool FreePose(const World2D& world, core::Rng* rng, core::Pose2* pose) {
  const WorldParams& params = world.params();
  const double r = params.robot_radius_m;
  const double min_d2 = (2.0 * r * kPlacementMargin) * (2.0 * r * kPlacementMargin);
  for (int attempt = 0; attempt < kPlacementAttempts; ++attempt) {
    const core::Vec2 p{rng->Uniform(r, params.world_size_m - r),
                       rng->Uniform(r, params.world_size_m - r)};
    const double heading = rng->Uniform(0.0, 360.0);
    bool free = true;
    for (const auto& entry : world.robots()) {
      if (SquaredDistance(p, entry.second.pose.position) < min_d2) {
        free = false;
        break;
      }
    }
    if (free) {
      *pose = core::Pose2{p, core::Angle(heading)};
      return true;
    }
  }
  return false;
}

std::vector<core::Pose2> PlaceRandom(int n, std::uint64_t seed, const WorldParams& params,
                                     std::string* error) {
  std::vector<core::Pose2> poses;
  if (n < 0) {
    SetError(error, "the number of robots must be >= 0");
    return poses;
  }
  const double r = params.robot_radius_m;
  const double min_d = 2.0 * r * kPlacementMargin;
  const double min_d2 = min_d * min_d;
  const double lo = r;
  const double hi = params.world_size_m - r;
  // An incremental grid of cell min_d: a conflict can only be in the 3x3 cells around.
  const int side = std::max(1, static_cast<int>(std::ceil(params.world_size_m / min_d)));
  std::vector<std::vector<std::size_t>> cells(static_cast<std::size_t>(side) * side);
  auto cell = [&](double v) {
    return std::min(side - 1, std::max(0, static_cast<int>(v / min_d)));
  };
  core::Rng rng(seed, kPlacementStream);
  poses.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    bool placed = false;
    for (int attempt = 0; attempt < kPlacementAttempts && !placed; ++attempt) {
      const core::Vec2 p{rng.Uniform(lo, hi), rng.Uniform(lo, hi)};
      const int cx = cell(p.x);
      const int cy = cell(p.y);
      bool free = true;
      for (int y = std::max(0, cy - 1); y <= std::min(side - 1, cy + 1) && free; ++y) {
        for (int x = std::max(0, cx - 1); x <= std::min(side - 1, cx + 1) && free; ++x) {
          for (std::size_t k : cells[static_cast<std::size_t>(y * side + x)]) {
            if (SquaredDistance(p, poses[k].position) < min_d2) {
              free = false;
              break;
            }
          }
        }
      }
      if (!free) continue;
      cells[static_cast<std::size_t>(cy * side + cx)].push_back(poses.size());
      poses.push_back(core::Pose2{p, core::Angle(rng.Uniform(0.0, 360.0))});
      placed = true;
    }
    if (!placed) {
      std::ostringstream os;
      os << "cannot place " << n << " robots of radius " << r << " m at random in a "
         << params.world_size_m << " m arena with centres " << min_d << " m apart (placed "
         << poses.size() << ")";
      SetError(error, os.str());
      return {};
    }
  }
  return poses;
}

std::vector<core::Pose2> PlaceCorner(int n, const WorldParams& params, std::string* error) {
  std::vector<core::Pose2> poses;
  if (n < 0) {
    SetError(error, "the number of robots must be >= 0");
    return poses;
  }
  if (n == 0) return poses;
  const double r = params.robot_radius_m;
  const double spacing = kCornerSpacingRadii * r;
  const double start = 2.0 * r;  // one radius of air to the walls
  const int cols = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n))));
  if (start + (cols - 1) * spacing > params.world_size_m - r) {
    std::ostringstream os;
    os << "cannot place " << n << " robots in a corner grid of spacing " << spacing
       << " m: it does not fit into the " << params.world_size_m << " m arena";
    SetError(error, os.str());
    return poses;
  }
  poses.reserve(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    const core::Vec2 p{start + (i % cols) * spacing, start + (i / cols) * spacing};
    poses.push_back(core::Pose2{p, core::Angle(kCornerHeadingDeg)});
  }
  return poses;
}

bool ParsePlacement(const std::string& text, std::vector<core::Pose2>* poses, std::string* error) {
  std::vector<core::Pose2> parsed;
  std::istringstream lines(text);
  std::string line;
  int number = 0;
  while (std::getline(lines, line)) {
    ++number;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream probe(line);
    std::string first;
    if (!(probe >> first)) continue;  // blank or comment only
    std::istringstream fields(line);
    double x = 0.0, y = 0.0, theta_deg = 0.0;
    std::string extra;
    if (!(fields >> x >> y >> theta_deg) || (fields >> extra) || !std::isfinite(x) ||
        !std::isfinite(y) || !std::isfinite(theta_deg)) {
      SetError(error, "line " + std::to_string(number) +
                          ": expected three finite numbers 'x y theta_deg' but got '" + line + "'");
      return false;
    }
    parsed.push_back(core::Pose2{{x, y}, core::Angle(theta_deg)});
  }
  *poses = std::move(parsed);
  return true;
}

bool PlaceInitialRobots(core::Placement placement, std::uint64_t seed,
                        const std::string& placement_file, int* robots, World2D* world,
                        std::string* error) {
  constexpr std::size_t kMaxRobots = 65536;
  std::vector<core::Pose2> poses;
  if (placement == core::Placement::kRandom) {
    poses = PlaceRandom(*robots, seed, world->params(), error);
  } else if (placement == core::Placement::kCorner) {
    poses = PlaceCorner(*robots, world->params(), error);
  } else {
    std::ifstream in(placement_file);
    std::stringstream text;
    if (!in || !(text << in.rdbuf())) {
      *error = "cannot read ~placement_file '" + placement_file + "'";
      return false;
    }
    if (!ParsePlacement(text.str(), &poses, error)) {
      *error = placement_file + ": " + *error;
      return false;
    }
    if (*robots < 0) *robots = static_cast<int>(poses.size());
    if (static_cast<int>(poses.size()) < *robots || poses.size() > kMaxRobots) {
      std::ostringstream os;
      os << placement_file << " has " << poses.size() << " poses but ~robots is " << *robots;
      *error = os.str();
      return false;
    }
    poses.resize(static_cast<std::size_t>(*robots));
  }
  if (static_cast<int>(poses.size()) != *robots) return false;  // error set by Place*
  for (std::size_t i = 0; i < poses.size(); ++i) {
    if (!world->Spawn(static_cast<std::uint16_t>(i), poses[i], error)) {
      *error = "robot " + std::to_string(i) + " (placement " + core::PlacementName(placement) +
               "): " + *error;
      return false;
    }
  }
  return true;
}

}  // namespace sim
}  // namespace swarm_transport
