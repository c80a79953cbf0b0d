#include "swarm_transport/ros/engine/mission_relay.h"

#include <algorithm>
#include <cstdio>

#include "swarm_transport/core/angle.h"
#include "swarm_transport/ros/common/conversions.h"

namespace swarm_transport {
namespace {

template <typename M>
std::vector<M> SortedBySender(std::vector<std::pair<std::string, M>> list) {
  std::stable_sort(list.begin(), list.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<M> out;
  out.reserve(list.size());
  for (auto& item : list) out.push_back(std::move(item.second));
  return out;
}

}  // namespace

std::string AnswerSender(std::uint16_t id) {
  char name[16];
  std::snprintf(name, sizeof(name), "robot_%05u", static_cast<unsigned>(id));
  return name;
}

void MissionRelay::AddOrder(const std::string& sender, const New_Mission& order) {
  pending_.emplace_back(sender, order);
}

bool MissionRelay::Started(const Standing& standing) {
  return standing.phase && standing.phase->state != Mission_Status::QUEUED;
}

void MissionRelay::Add(const std::string& sender, const Update_Object& msg) {
  Push(sender, msg, &updates_);
  const auto it = standing_.find(msg.mission_id);
  if (it == standing_.end()) return;
  it->second.order.object_position_x = msg.object_position_x;
  it->second.order.object_position_y = msg.object_position_y;
}

void MissionRelay::Add(const std::string& sender, const Delete_Object& msg) {
  Push(sender, msg, &deletes_);
  standing_.erase(msg.mission_id);
}

void MissionRelay::Add(const std::string& sender, const Mission_Status& msg) {
  Push(sender, msg, &statuses_);
  const auto it = standing_.find(msg.mission_id);
  if (it == standing_.end()) return;
  switch (msg.state) {
    case Mission_Status::DONE:
    case Mission_Status::ABORTED:
      standing_.erase(it);
      return;
    case Mission_Status::REJECTED:
      // Of a mission that never started: it ends. Of one that did: a refused duplicate of its
      // id (the robots ignore it for the live mission too).
      if (!Started(it->second)) standing_.erase(it);
      return;
    default:
      if (msg.state > Mission_Status::UNLOADING) return;  // no phase
      // Phases only move forward (as the robots take them: core::MissionAgent::OnStatus).
      if (!it->second.phase || msg.state > it->second.phase->state) it->second.phase = msg;
      return;
  }
}

void MissionRelay::AddAnswer(std::uint16_t id, const Tick_Answer& answer) {
  const std::string sender = AnswerSender(id);
  for (const Update_Object& m : answer.object_updates) Add(sender, m);
  for (const Robot_Freeze& m : answer.freezes) Add(sender, m);
  for (const Robot_Continue& m : answer.continues) Add(sender, m);
  for (const Delete_Object& m : answer.object_deletes) Add(sender, m);
  for (const Mission_Status& m : answer.statuses) Add(sender, m);
}

std::vector<New_Mission> MissionRelay::ReleaseOrders(std::uint64_t tick) {
  std::vector<New_Mission> released;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < pending_.size(); ++i) {
    auto& entry = pending_[i];
    if (entry.second.start_tick > tick) {
      if (kept != i) pending_[kept] = std::move(entry);
      ++kept;
      continue;
    }
    released.push_back(entry.second);
    // A started mission keeps its order (one with its id now is a duplicate the robots refuse).
    const auto standing = standing_.find(entry.second.mission_id);
    if (standing == standing_.end() || !Started(standing->second)) {
      standing_[entry.second.mission_id] = Standing{entry.second, std::nullopt};
    }
    Push(entry.first, entry.second, &missions_);
  }
  pending_.resize(kept);
  return released;
}

void MissionRelay::Sort() {
  round_.missions = SortedBySender(missions_);
  round_.object_updates = SortedBySender(updates_);
  round_.object_deletes = SortedBySender(deletes_);
  round_.freezes = SortedBySender(freezes_);
  round_.continues = SortedBySender(continues_);
  round_.mission_events = SortedBySender(events_);
  round_.statuses = SortedBySender(statuses_);
  sorted_ = true;
}

void MissionRelay::Fill(Neighbors* round) {
  if (!sorted_) Sort();
  round->missions = round_.missions;
  round->object_updates = round_.object_updates;
  round->object_deletes = round_.object_deletes;
  round->freezes = round_.freezes;
  round->continues = round_.continues;
  round->mission_events = round_.mission_events;
  round->statuses = round_.statuses;
}

void MissionRelay::FillStanding(Neighbors* round) const {
  const auto carries = [](const auto& list, std::uint16_t id) {
    return std::any_of(list.begin(), list.end(),
                       [id](const auto& m) { return m.mission_id == id; });
  };
  for (const auto& kv : standing_) {
    if (carries(round->missions, kv.first)) continue;  // released in this round
    round->missions.push_back(kv.second.order);
    if (kv.second.phase && !carries(round->statuses, kv.first)) {
      round->statuses.push_back(*kv.second.phase);
    }
  }
}

void MissionRelay::Clear() {
  missions_.clear();
  updates_.clear();
  deletes_.clear();
  freezes_.clear();
  continues_.clear();
  events_.clear();
  statuses_.clear();
  sorted_ = false;
}

TuningRelay::TuningRelay(const core::SwarmConfig& config) : config_(config) {}

std::string TuningRelay::Propose(const core::FlockingTuning& tuning) {
  if (tuning == newest()) return "";
  const std::string why = config_.Retune(tuning);
  if (why.empty()) pending_ = true;
  return why;
}

std::optional<Flocking_Tuning> TuningRelay::BeginRound(std::uint64_t tick) {
  if (!pending_) return std::nullopt;
  pending_ = false;
  if (current_ && ToFlockingTuning(*current_) == newest()) return std::nullopt;  // changed back
  current_ = ToTuningMsg(newest(), generation() + 1, tick);
  return current_;
}

void TuningRelay::Fill(Neighbors* round) const {
  round->tuning.clear();
  if (current_) round->tuning.push_back(*current_);
}

std::string RelayedPositions::Take(const Robot_Position& msg) {
  if (Ignored(msg)) return "";
  if (!IsFinite(msg)) return "a non-finite value";
  if (msg.type != Robot_Position::TYPE_VIRTUAL && msg.type != Robot_Position::TYPE_STATIST) {
    return "unknown type " + std::to_string(msg.type);
  }
  Robot_Position p = msg;
  p.angle = static_cast<float>(core::Angle(p.angle).degrees());
  if (p.angle >= 360.0f) p.angle = 0.0f;
  positions_[{p.robot_id, p.sub_id}] = p;
  return "";
}

bool RelayedPositions::Erase(std::uint16_t robot_id, std::uint8_t sub_id) {
  return positions_.erase({robot_id, sub_id}) > 0;
}

void RelayedPositions::EraseCopiesOf(std::uint16_t robot_id) {
  for (auto r = positions_.begin(); r != positions_.end();) {
    if (r->first.first == robot_id && r->second.type == Robot_Position::TYPE_VIRTUAL) {
      r = positions_.erase(r);
    } else {
      ++r;
    }
  }
}

std::vector<sim::RadioExtra> RelayedPositions::Extras() const {
  std::vector<sim::RadioExtra> extras;
  extras.reserve(positions_.size());
  for (const auto& entry : positions_) {
    sim::RadioExtra e;
    e.virtual_copy = entry.second.type == Robot_Position::TYPE_VIRTUAL;
    e.owner = entry.second.robot_id;
    e.position = {entry.second.pos_x, entry.second.pos_y};
    extras.push_back(e);
  }
  return extras;
}

std::vector<Robot_Position> RelayedPositions::AtOwners(
    const std::vector<long>& owner, const std::vector<Robot_Position>& truth) const {
  std::vector<Robot_Position> relayed;
  relayed.reserve(positions_.size());
  std::size_t k = 0;
  for (const auto& entry : positions_) {
    Robot_Position p = entry.second;
    const long o = k < owner.size() ? owner[k] : -1;
    ++k;
    if (o >= 0) {
      p.pos_x = truth[static_cast<std::size_t>(o)].pos_x;
      p.pos_y = truth[static_cast<std::size_t>(o)].pos_y;
      p.angle = truth[static_cast<std::size_t>(o)].angle;
    }
    relayed.push_back(p);
  }
  return relayed;
}

}  // namespace swarm_transport
