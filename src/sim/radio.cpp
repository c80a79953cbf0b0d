#include "swarm_transport/sim/radio.h"

#include <algorithm>
#include <utility>

namespace swarm_transport {
namespace sim {

Radio::Radio(const RadioParams& params, core::Rng* loss_rng)
    : params_(params), loss_rng_(loss_rng) {}

long Radio::IndexOf(std::uint16_t id) const {
  const auto it = std::lower_bound(ids_.begin(), ids_.end(), id);
  return it != ids_.end() && *it == id ? it - ids_.begin() : -1;
}

bool Radio::Lost() { return params_.loss > 0.0 && loss_rng_->Uniform(0.0, 1.0) < params_.loss; }

void Radio::Begin(const World2D& world, std::vector<RadioExtra> extras,
                  const LiveMissions& missions, const std::set<std::uint16_t>& quiet) {
  ids_.clear();
  positions_.clear();
  ids_.reserve(world.size());
  positions_.reserve(world.size());
  for (const auto& entry : world.robots()) {
    ids_.push_back(entry.first);
    positions_.push_back(entry.second.pose.position);
  }
  extras_ = std::move(extras);
  extra_owner_.assign(extras_.size(), -1);
  for (std::size_t k = 0; k < extras_.size(); ++k) {
    if (!extras_[k].virtual_copy) continue;
    extra_owner_[k] = IndexOf(extras_[k].owner);
    if (extra_owner_[k] < 0) continue;
    // At the owner's pose as a Robot_Position carries it (float32), so that the range test
    // sees what a robot hears.
    const core::Vec2 owner = positions_[static_cast<std::size_t>(extra_owner_[k])];
    extras_[k].position = {static_cast<float>(owner.x), static_cast<float>(owner.y)};
  }
  // Missions in id order; a robot's missions in that order too.
  member_lists_.clear();
  missions_of_.assign(ids_.size(), {});
  for (const auto& entry : missions) {
    const std::size_t m = member_lists_.size();
    member_lists_.push_back(entry.second.members);
    for (std::uint16_t member : entry.second.members) {
      const long i = IndexOf(member);
      if (i >= 0) missions_of_[static_cast<std::size_t>(i)].push_back(m);
    }
  }
  world.NeighbourIndices(params_.range_m, &table_);
  quiet_.assign(ids_.size(), 0);
  if (!quiet.empty()) {
    for (std::size_t i = 0; i < ids_.size(); ++i) quiet_[i] = quiet.count(ids_[i]) > 0 ? 1 : 0;
    // Nobody hears a quiet robot: it leaves every list (its own list stays).
    std::uint32_t read = 0;
    std::uint32_t write = 0;
    for (std::size_t i = 0; i < ids_.size(); ++i) {
      const std::uint32_t end = table_.start[i + 1];
      table_.start[i] = write;
      for (; read < end; ++read) {
        if (!quiet_[table_.index[read]]) table_.index[write++] = table_.index[read];
      }
    }
    table_.start[ids_.size()] = write;
    table_.index.resize(write);
  }
  heard_.assign(ids_.size(), 0);
  touched_.clear();
}

void Radio::Hear(std::size_t i, RadioRound* out) {
  out->in_range.clear();
  out->chain.clear();
  out->extras.clear();
  out->peers.clear();
  const std::uint16_t id = ids_[i];
  // Losses are drawn only when there are any (Lost() itself is a call through the library's
  // symbol table); local pointers, as the lists' pushes would make the compiler reload them.
  const bool lossy = params_.loss > 0.0;
  char* const heard = heard_.data();
  const auto mark = [this, heard](std::size_t j) {
    heard[j] = 1;
    touched_.push_back(j);
  };
  const std::uint32_t* const start = table_.start.data();
  const std::uint32_t* const index = table_.index.data();
  for (std::uint32_t k = start[i]; k < start[i + 1]; ++k) {
    if (lossy && Lost()) continue;  // a lost neighbour may still be heard as a mission peer
    const std::size_t j = index[k];
    out->in_range.push_back(j);
    mark(j);
  }
  // A chain's far end: what the robots in range heard in range, passed on hop by hop.
  if (params_.hops > 1) {
    mark(i);
    ring_.clear();
    for (std::uint32_t k = start[i]; k < start[i + 1]; ++k) ring_.push_back(index[k]);
    std::size_t ring_begin = 0;
    for (int hop = 2; hop <= params_.hops && ring_begin < ring_.size(); ++hop) {
      const std::size_t ring_end = ring_.size();
      for (std::size_t k = ring_begin; k < ring_end; ++k) {
        const std::size_t near = ring_[k];
        const std::uint32_t near_end = start[near + 1];
        for (std::uint32_t f = start[near]; f < near_end; ++f) {
          const std::size_t j = index[f];
          if (heard[j]) continue;
          ring_.push_back(j);
          if (lossy && Lost()) {
            // Passed on hop by hop, but its own position lost: a mission peer still reaches it
            // over the mission channel below (2: visited, not heard).
            heard[j] = 2;
            touched_.push_back(j);
          } else {
            mark(j);
            out->chain.push_back(j);
          }
        }
      }
      ring_begin = ring_end;
    }
  }
  const core::Vec2 self = positions_[i];
  const double range2 = params_.range_m * params_.range_m;
  for (std::size_t k = 0; k < extras_.size(); ++k) {
    const RadioExtra& e = extras_[k];
    if (e.virtual_copy) {
      if (e.owner == id) continue;  // a robot does not hear its own copies
      const double dx = e.position.x - self.x;
      const double dy = e.position.y - self.y;
      if (dx * dx + dy * dy > range2) continue;
    }
    if (lossy && Lost()) continue;
    out->extras.push_back(k);
  }
  // The mission channel: every other member of its missions, wherever it is.
  for (std::size_t m : missions_of_[i]) {
    for (std::uint16_t member : member_lists_[m]) {
      const long j = IndexOf(member);
      if (member == id || j < 0 || heard_[static_cast<std::size_t>(j)] == 1 ||
          quiet_[static_cast<std::size_t>(j)]) {
        continue;
      }
      mark(static_cast<std::size_t>(j));
      out->peers.push_back(static_cast<std::size_t>(j));
    }
  }
  for (std::size_t j : touched_) heard_[j] = 0;
  touched_.clear();
}

}  // namespace sim
}  // namespace swarm_transport
