// Where a world's robots start: random, corner or file placement, and a free pose for one more.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <sstream>
#include <utility>

#include "swarm_transport/core/random.h"
#include "swarm_transport/sim/world2d.h"

namespace swarm_transport {
namespace sim {
namespace {

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

}  // namespace

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
  // An incremental grid of cell min_d: a conflict can only be in the 3x3 cells around. The
  // cells are hashed into about twice as many buckets as robots, each bucket a chain through
  // `next` (memory O(n): a dense table of 10,000 robots' arena at the thesis's density had 1.8
  // million cells); a bucket may hold other cells' robots too, which the distance check drops.
  const int side = std::max(1, static_cast<int>(std::ceil(params.world_size_m / min_d)));
  auto cell = [&](double v) {
    return std::min(side - 1, std::max(0, static_cast<int>(v / min_d)));
  };
  std::size_t buckets = 16;
  while (buckets < 2 * static_cast<std::size_t>(n)) buckets *= 2;
  const auto bucket = [buckets](int x, int y) {
    const std::uint64_t h =
        (static_cast<std::uint64_t>(static_cast<std::uint32_t>(x)) * 0x9E3779B97F4A7C15ULL) ^
        (static_cast<std::uint64_t>(static_cast<std::uint32_t>(y)) * 0xC2B2AE3D27D4EB4FULL);
    return static_cast<std::size_t>((h ^ (h >> 29)) & (buckets - 1));
  };
  constexpr std::size_t kNone = static_cast<std::size_t>(-1);
  std::vector<std::size_t> head(buckets, kNone);
  std::vector<std::size_t> next;
  next.reserve(static_cast<std::size_t>(n));
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
          for (std::size_t k = head[bucket(x, y)]; k != kNone; k = next[k]) {
            if (SquaredDistance(p, poses[k].position) < min_d2) {
              free = false;
              break;
            }
          }
        }
      }
      if (!free) continue;
      std::size_t& first = head[bucket(cx, cy)];
      next.push_back(first);
      first = poses.size();
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
