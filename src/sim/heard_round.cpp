#include "swarm_transport/sim/heard_round.h"

#include <algorithm>
#include <string>
#include <utility>
#include <variant>

namespace swarm_transport {
namespace sim {
namespace {

// The nearest centre inside the arena a world robot may have.
core::Vec2 Inside(double x, double y, const WorldParams& world) {
  const double lo = world.robot_radius_m;
  const double hi = world.world_size_m - world.robot_radius_m;
  return {std::max(lo, std::min(hi, x)), std::max(lo, std::min(hi, y))};
}

}  // namespace

std::uint64_t HeardLossStream(std::uint16_t id) { return kRadioLossStream + 1 + id; }

HeardRound::HeardRound(std::uint16_t self, const RadioParams& radio, const WorldParams& world,
                       double heard_timeout_s, std::uint64_t seed)
    : self_(self),
      world_params_(world),
      heard_timeout_s_(heard_timeout_s),
      loss_rng_(seed, HeardLossStream(self)),
      radio_(radio, &loss_rng_) {
  known_.insert(self);
}

bool HeardRound::Hear(const core::Position& position, double now_s) {
  if (!core::IsFinite(position)) return false;
  if (position.robot_id == self_ && position.type == core::Position::kPhysical) return false;
  heard_[{position.robot_id, position.sub_id}] = Heard{position, now_s};
  if (position.type != core::Position::kPhysical) return false;
  return known_.insert(position.robot_id).second;
}

void HeardRound::Take(const core::MissionMessage& message) {
  if (const auto* order = std::get_if<core::MissionSpec>(&message)) {
    LiveMission& live = missions_[order->id];
    live.members = order->Assigned();
  } else if (const auto* deleted = std::get_if<core::ObjectDelete>(&message)) {
    missions_.erase(deleted->mission_id);
  }
}

void HeardRound::Assemble(std::uint64_t tick, double now_s, const core::Pose2& self,
                          const core::Velocity& velocity, core::Round* out) {
  World2D world(world_params_);
  std::string error;
  world.Spawn(self_, {Inside(self.position.x, self.position.y, world_params_), self.heading},
              &error);
  std::vector<RadioExtra> extras;
  extras_.clear();
  std::map<std::uint16_t, core::Position> fresh;
  for (const auto& entry : heard_) {
    const Heard& h = entry.second;
    if (now_s - h.at_s > heard_timeout_s_) continue;
    const core::Position& p = h.position;
    if (p.type == core::Position::kPhysical) {
      if (world.Spawn(p.robot_id, {Inside(p.x, p.y, world_params_), core::Angle(p.angle_deg)},
                      &error)) {
        fresh[p.robot_id] = p;
      }
    } else {
      RadioExtra e;
      e.virtual_copy = p.type == core::Position::kVirtual;
      e.owner = p.robot_id;
      e.position = {p.x, p.y};
      extras.push_back(e);
      extras_.push_back(p);
    }
  }
  robots_.clear();
  std::size_t self_index = 0;
  for (const auto& entry : world.robots()) {
    if (entry.first == self_) self_index = robots_.size();
    robots_.push_back(entry.first == self_ ? core::Position() : fresh[entry.first]);
  }
  radio_.Begin(world, std::move(extras), missions_);
  radio_.Hear(self_index, &radio_round_);
  out->tick = tick;
  out->sim_time = now_s;
  out->pose = core::OwnPoseOf(self, velocity);
  out->robots.clear();
  for (std::size_t j : radio_round_.in_range) out->robots.push_back(robots_[j]);
  for (std::size_t e : radio_round_.extras) out->robots.push_back(extras_[e]);
  out->relayed.clear();
  for (std::size_t j : radio_round_.chain) out->relayed.push_back(robots_[j]);
  out->mission_peers.clear();
  for (std::size_t j : radio_round_.peers) out->mission_peers.push_back(robots_[j]);
  out->messages.clear();
  out->tuning.reset();
}

std::pair<std::size_t, std::size_t> HeardRound::Delivered(const core::Round& round, double now_s,
                                                          double within_s) const {
  std::size_t expected = 0;
  std::size_t delivered = 0;
  for (const core::Position& p : round.robots) {
    if (p.type != core::Position::kPhysical) continue;
    ++expected;
    const auto it = heard_.find({p.robot_id, 0});
    if (it != heard_.end() && now_s - it->second.at_s <= within_s) ++delivered;
  }
  return {expected, delivered};
}

}  // namespace sim
}  // namespace swarm_transport
