// What the batch runs write besides the recorder's files: result.json (a small JSON writer)
// and a leader run's leader_track.csv (the experiment worker's LeaderTrack: thesis Fig. 7.6).
#ifndef SWARM_TRANSPORT_ROS_BATCH_FILES_H_
#define SWARM_TRANSPORT_ROS_BATCH_FILES_H_

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "swarm_transport/core/geometry.h"
#include "swarm_transport/core/metrics.h"
#include "swarm_transport/core/run_metrics.h"

namespace swarm_transport {

// JSON text of a string (quoted, escaped) and of a number (null when not finite; a float stays
// a float for the reader: 0.0, not 0).
std::string JsonString(const std::string& s);
std::string JsonNumber(double v);

// A JSON object: members in the order added; values are JSON text.
class JsonObject {
 public:
  JsonObject& Add(const std::string& key, const std::string& json) {
    members_.emplace_back(key, json);
    return *this;
  }
  // Nested objects get `indent` before their members.
  std::string Text(const std::string& indent = "") const;

 private:
  std::vector<std::pair<std::string, std::string>> members_;
};

// The leader's progress along its straight path and the size of its swarm at every tick (the
// experiment worker's LeaderTrack: thesis Fig. 7.6).
class LeaderTrack {
 public:
  LeaderTrack(std::uint16_t leader, core::Vec2 target, double local_range_m)
      : leader_(leader), target_(target), local_range_m_(local_range_m) {}

  void Add(const core::MetricsFrame& frame) {
    const long li = frame.IndexOf(leader_);
    if (li < 0) return;
    const core::Vec2 lp = frame.positions[static_cast<std::size_t>(li)];
    if (!start_) start_ = lp;
    const double total = std::hypot(target_.x - start_->x, target_.y - start_->y);
    const double left = std::hypot(target_.x - lp.x, target_.y - lp.y);
    const double progress = total > 0.0 ? std::min(1.0, std::max(0.0, 1.0 - left / total)) : 1.0;
    const core::SwarmComponents swarms(frame.positions, local_range_m_);
    const std::size_t swarm = swarms.SizeOfSwarmOf(static_cast<std::size_t>(li)) - 1;
    rows_.push_back({frame.tick, progress, swarm, swarms.SwarmCount()});
  }

  // The track ends at the arrival: later rows go, the arrival's row counts as the whole path.
  void Arrived(std::uint64_t tick) {
    rows_.erase(
        std::remove_if(rows_.begin(), rows_.end(), [tick](const Row& r) { return r.tick > tick; }),
        rows_.end());
    if (!rows_.empty() && rows_.back().tick == tick) rows_.back().fraction = 1.0;
  }

  bool Write(const std::string& path) const {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (f == nullptr) return false;
    std::fputs("tick,path_fraction,leader_swarm,swarm_count\n", f);
    for (const Row& r : rows_) {
      std::fprintf(f, "%llu,%.6f,%zu,%zu\n", static_cast<unsigned long long>(r.tick), r.fraction,
                   r.swarm, r.count);
    }
    return std::fclose(f) == 0;
  }

 private:
  struct Row {
    std::uint64_t tick;
    double fraction;
    std::size_t swarm;
    std::size_t count;
  };
  std::uint16_t leader_;
  core::Vec2 target_;
  double local_range_m_;
  std::optional<core::Vec2> start_;
  std::vector<Row> rows_;
};

}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_ROS_BATCH_FILES_H_
