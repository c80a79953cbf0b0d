#include "swarm_transport/sim/mission_relay.h"

#include <algorithm>
#include <cstdio>

#include "swarm_transport/core/angle.h"

namespace swarm_transport {
namespace sim {

using core::MissionMessage;
using core::MissionPhase;

std::string AnswerSender(std::uint16_t id) {
  char name[16];
  std::snprintf(name, sizeof(name), "robot_%05u", static_cast<unsigned>(id));
  return name;
}

void MissionRelay::AddOrder(const std::string& sender, const core::MissionSpec& order,
                            std::uint64_t start_tick) {
  pending_.push_back(Held{sender, order, start_tick});
}

void MissionRelay::Push(const std::string& sender, const MissionMessage& message) {
  lists_[message.index()].emplace_back(sender, message);
  sorted_ = false;
}

void MissionRelay::Add(const std::string& sender, const MissionMessage& message) {
  if (const auto* order = std::get_if<core::MissionSpec>(&message)) {
    AddOrder(sender, *order, 0);
    return;
  }
  Push(sender, message);
  std::visit([this](const auto& m) { Note(m); }, message);
}

bool MissionRelay::Started(const Standing& standing) {
  return standing.phase && *standing.phase != MissionPhase::kQueued;
}

void MissionRelay::Note(const core::ObjectUpdate& m) {
  const auto it = standing_.find(m.mission_id);
  if (it != standing_.end()) it->second.order.object_centre = m.centre;
}

void MissionRelay::Note(const core::ObjectDelete& m) { standing_.erase(m.mission_id); }

void MissionRelay::Note(const core::PhaseStatus& m) {
  const auto it = standing_.find(m.mission_id);
  if (it == standing_.end()) return;
  switch (m.phase) {
    case MissionPhase::kDone:
    case MissionPhase::kAborted:
      standing_.erase(it);
      return;
    case MissionPhase::kRejected:
      // Of a mission that never started: it ends. Of one that did: a refused duplicate of its
      // id (the robots ignore it for the live mission too).
      if (!Started(it->second)) standing_.erase(it);
      return;
    default:
      if (m.phase > MissionPhase::kUnloading) return;  // no phase
      it->second.lost.insert(m.lost.begin(), m.lost.end());
      // Phases only move forward (as the robots take them: core::MissionAgent::OnStatus).
      if (!it->second.phase || m.phase > *it->second.phase) it->second.phase = m.phase;
      return;
  }
}

void MissionRelay::AddAnswer(std::uint16_t id, const core::Answer& answer) {
  const std::string sender = AnswerSender(id);
  for (const MissionMessage& m : answer.messages) Add(sender, m);
  for (const core::StatusReport& s : answer.statuses) {
    Add(sender, core::PhaseStatus{s.mission_id, s.phase, s.lost});
  }
}

std::vector<core::MissionSpec> MissionRelay::ReleaseOrders(std::uint64_t tick) {
  std::vector<core::MissionSpec> released;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    Held& held = pending_[i];
    if (held.start_tick > tick) {
      if (kept != i) pending_[kept] = std::move(held);
      ++kept;
      continue;
    }
    released.push_back(held.order);
    // A started mission keeps its order (one with its id now is a duplicate the robots refuse).
    const auto standing = standing_.find(held.order.id);
    if (standing == standing_.end() || !Started(standing->second)) {
      standing_[held.order.id] = Standing{held.order, std::nullopt, {}};
    }
    Push(held.sender, held.order);
  }
  pending_.resize(kept);
  return released;
}

void MissionRelay::Sort() {
  round_.clear();
  for (List& list : lists_) {
    std::stable_sort(list.begin(), list.end(),
                     [](const auto& a, const auto& b) { return a.first < b.first; });
    for (const auto& item : list) round_.push_back(item.second);
  }
  sorted_ = true;
}

void MissionRelay::Fill(core::Round* round) {
  if (!sorted_) Sort();
  round->messages = round_;
}

std::size_t MissionRelay::FillStanding(core::Round* round) const {
  std::vector<MissionMessage>& messages = round->messages;
  const auto carries = [&messages](std::uint16_t id, auto kind) {
    using M = decltype(kind);
    return std::any_of(messages.begin(), messages.end(), [id](const MissionMessage& m) {
      const M* typed = std::get_if<M>(&m);
      return typed != nullptr && core::MissionIdOf(m) == id;
    });
  };
  std::vector<MissionMessage> orders;
  std::vector<MissionMessage> phases;
  for (const auto& kv : standing_) {
    if (carries(kv.first, core::MissionSpec())) continue;  // released in this round
    orders.push_back(kv.second.order);
    if (kv.second.phase && !carries(kv.first, core::PhaseStatus())) {
      // With the robots lost so far: a robot process started again under a lost robot's id
      // (a respawn) must not lead or count in the mission it was lost from.
      phases.push_back(core::PhaseStatus{
          kv.first, *kv.second.phase,
          std::vector<std::uint16_t>(kv.second.lost.begin(), kv.second.lost.end())});
    }
  }
  // Orders come first in a round, phases last.
  const auto after_orders = std::find_if(
      messages.begin(), messages.end(),
      [](const MissionMessage& m) { return !std::holds_alternative<core::MissionSpec>(m); });
  messages.insert(after_orders, orders.begin(), orders.end());
  messages.insert(messages.end(), phases.begin(), phases.end());
  return orders.size();
}

void MissionRelay::Clear() {
  for (List& list : lists_) list.clear();
  sorted_ = false;
}

TuningRelay::TuningRelay(const core::SwarmConfig& config) : config_(config) {}

std::string TuningRelay::Propose(const core::FlockingTuning& tuning) {
  if (tuning == newest()) return "";
  const std::string why = config_.Retune(tuning);
  if (why.empty()) pending_ = true;
  return why;
}

std::optional<core::TuningGeneration> TuningRelay::BeginRound(std::uint64_t tick) {
  if (!pending_) return std::nullopt;
  pending_ = false;
  if (current_ && current_->tuning == newest()) return std::nullopt;  // changed back
  current_ = core::TuningGeneration{generation() + 1, tick, newest()};
  return current_;
}

std::string RelayedPositions::Take(const core::Position& position) {
  if (Ignored(position)) {
    if (position.copies > 0) {
      copies_[position.robot_id] = position.copies;
    } else if (!copies_.empty()) {
      copies_.erase(position.robot_id);
    }
    return "";
  }
  if (!core::IsFinite(position)) return "a non-finite value";
  if (position.type != core::Position::kVirtual && position.type != core::Position::kStatist) {
    return "unknown type " + std::to_string(position.type);
  }
  core::Position p = position;
  p.angle_deg = static_cast<float>(core::Angle(p.angle_deg).degrees());
  if (p.angle_deg >= 360.0f) p.angle_deg = 0.0f;
  positions_[{p.robot_id, p.sub_id}] = p;
  return "";
}

bool RelayedPositions::Erase(std::uint16_t robot_id, std::uint8_t sub_id) {
  return positions_.erase({robot_id, sub_id}) > 0;
}

void RelayedPositions::EraseCopiesOf(std::uint16_t robot_id) {
  copies_.erase(robot_id);
  for (auto r = positions_.begin(); r != positions_.end();) {
    if (r->first.first == robot_id && r->second.type == core::Position::kVirtual) {
      r = positions_.erase(r);
    } else {
      ++r;
    }
  }
}

std::vector<RadioExtra> RelayedPositions::Extras() const {
  std::vector<RadioExtra> extras;
  extras.reserve(positions_.size());
  for (const auto& entry : positions_) {
    RadioExtra e;
    e.virtual_copy = entry.second.type == core::Position::kVirtual;
    e.owner = entry.second.robot_id;
    e.position = {entry.second.x, entry.second.y};
    extras.push_back(e);
  }
  return extras;
}

std::vector<core::Position> RelayedPositions::AtOwners(
    const std::vector<long>& owner, const std::vector<core::Position>& truth) const {
  std::vector<core::Position> relayed;
  relayed.reserve(positions_.size());
  std::size_t k = 0;
  for (const auto& entry : positions_) {
    core::Position p = entry.second;
    const long o = k < owner.size() ? owner[k] : -1;
    ++k;
    if (o >= 0) {
      const core::Position& at = truth[static_cast<std::size_t>(o)];
      p.x = at.x;
      p.y = at.y;
      p.angle_deg = at.angle_deg;
    }
    relayed.push_back(p);
  }
  return relayed;
}

}  // namespace sim
}  // namespace swarm_transport
