#include "swarm_transport/sim/lockstep_engine.h"

#include <algorithm>
#include <variant>

namespace swarm_transport {
namespace sim {

LockstepEngine::LockstepEngine(const World2D* world, Radio* radio, LiveMissions* missions)
    : world_(world), radio_(radio), missions_(missions) {}

std::vector<std::pair<core::MissionSpec, std::string>> LockstepEngine::ReleaseOrders(
    std::uint64_t tick) {
  std::vector<std::pair<core::MissionSpec, std::string>> refused;
  for (core::MissionSpec& order : relay_.ReleaseOrders(tick)) {
    std::string why = RegisterMission(order, *world_, missions_);
    if (!why.empty()) refused.emplace_back(std::move(order), std::move(why));
  }
  return refused;
}

void LockstepEngine::BeginRound(std::uint64_t tick, double sim_time,
                                const RelayedPositions* relayed,
                                const std::set<std::uint16_t>& quiet) {
  tick_ = tick;
  sim_time_ = sim_time;
  const auto& robots = world_->robots();
  truth_.clear();
  truth_.reserve(robots.size());
  for (const auto& entry : robots)
    truth_.push_back(core::PositionOf(entry.first, entry.second.pose));
  // The virtual copies robots announce travel on their own positions (SPEC 9.2): from their
  // answers in lock-step, from their /flock/position in real time.
  if (!copies_.empty()) StampCopies(copies_);
  if (relayed != nullptr && !relayed->copies().empty()) StampCopies(relayed->copies());
  radio_->Begin(*world_, relayed != nullptr ? relayed->Extras() : std::vector<RadioExtra>(),
                *missions_, quiet);
  // Virtual copies are relayed at their owner's true pose, the others where announced.
  relayed_ = relayed != nullptr ? relayed->AtOwners(radio_->extra_owner(), truth_)
                                : std::vector<core::Position>();
}

void LockstepEngine::StampCopies(const std::map<std::uint16_t, std::uint8_t>& copies) {
  const auto by_id = [](const core::Position& p, std::uint16_t id) { return p.robot_id < id; };
  for (const auto& entry : copies) {
    const auto it = std::lower_bound(truth_.begin(), truth_.end(), entry.first, by_id);
    if (it != truth_.end() && it->robot_id == entry.first) it->copies = entry.second;
  }
}

std::size_t LockstepEngine::Round(std::size_t index, bool connected, core::Round* out) {
  radio_->Hear(index, &heard_);
  const Robot& robot = world_->robots().nth(index)->second;
  out->tick = tick_;
  out->sim_time = sim_time_;
  out->pose = core::OwnPoseOf(robot.pose, robot.last_velocity);
  out->robots.clear();
  out->robots.reserve(heard_.in_range.size() + heard_.extras.size());
  for (std::size_t j : heard_.in_range) out->robots.push_back(truth_[j]);
  for (std::size_t e : heard_.extras) out->robots.push_back(relayed_[e]);
  out->relayed.clear();
  out->relayed.reserve(heard_.chain.size());
  for (std::size_t j : heard_.chain) out->relayed.push_back(truth_[j]);
  out->mission_peers.clear();
  out->mission_peers.reserve(heard_.peers.size());
  for (std::size_t j : heard_.peers) out->mission_peers.push_back(truth_[j]);
  out->tuning.reset();
  relay_.Fill(out);
  return connected ? relay_.FillStanding(out) : 0;
}

void LockstepEngine::TakeAnswers(
    Answers* answers, const std::function<void(std::uint16_t, const core::Answer&)>& observe) {
  const auto by_id = [](const auto& a, const auto& b) { return a.first < b.first; };
  // Answers by id already (the batch runs' and most ticks'): a stable sort would still move
  // every answer twice.
  if (!std::is_sorted(answers->begin(), answers->end(), by_id)) {
    std::stable_sort(answers->begin(), answers->end(), by_id);
  }
  for (const auto& entry : *answers) {
    const core::Answer& a = entry.second;
    // Most answers relay nothing: no sender name to format for them.
    if (!a.messages.empty() || !a.statuses.empty()) relay_.AddAnswer(entry.first, a);
    if (a.copies > 0) {
      copies_[entry.first] = a.copies;
    } else if (!copies_.empty()) {
      copies_.erase(entry.first);
    }
    for (const core::MissionMessage& m : a.messages) {
      if (const auto* u = std::get_if<core::ObjectUpdate>(&m)) {
        UpdateMissionObject(u->mission_id, u->centre, *world_, missions_);
      } else if (const auto* d = std::get_if<core::ObjectDelete>(&m)) {
        missions_->erase(d->mission_id);
      }
    }
    if (observe) observe(entry.first, a);
  }
  answers->clear();
}

}  // namespace sim
}  // namespace swarm_transport
