#include "swarm_transport/ros/engine/lockstep_engine.h"

#include <algorithm>

#include "swarm_transport/ros/common/conversions.h"

namespace swarm_transport {

LockstepEngine::LockstepEngine(const sim::World2D* world, sim::Radio* radio,
                               sim::LiveMissions* missions)
    : world_(world), radio_(radio), missions_(missions) {}

std::vector<std::pair<New_Mission, std::string>> LockstepEngine::ReleaseOrders(std::uint64_t tick) {
  std::vector<std::pair<New_Mission, std::string>> refused;
  for (New_Mission& order : relay_.ReleaseOrders(tick)) {
    std::string why = sim::RegisterMission(ToMissionSpec(order), *world_, missions_);
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
    truth_.push_back(ToRobotPosition(entry.first, entry.second.pose));
  radio_->Begin(*world_, relayed != nullptr ? relayed->Extras() : std::vector<sim::RadioExtra>(),
                *missions_, quiet);
  // Virtual copies are relayed at their owner's true pose, the others where announced.
  relayed_ = relayed != nullptr ? relayed->AtOwners(radio_->extra_owner(), truth_)
                                : std::vector<Robot_Position>();
}

std::size_t LockstepEngine::Round(std::size_t index, bool connected, Neighbors* out) {
  radio_->Hear(index, &heard_);
  const sim::Robot& robot = world_->robots().nth(index)->second;
  *out = RadioRoundMessage(tick_, sim_time_, robot, heard_, truth_, relayed_);
  relay_.Fill(out);
  if (!connected) return 0;
  const std::size_t relayed = out->missions.size();
  relay_.FillStanding(out);
  return out->missions.size() - relayed;
}

void LockstepEngine::TakeAnswers(
    Answers* answers, const std::function<void(std::uint16_t, const Tick_Answer&)>& observe) {
  const auto by_id = [](const auto& a, const auto& b) { return a.first < b.first; };
  // Answers by id already (the batch runs' and most ticks'): a stable sort would still move
  // every answer twice.
  if (!std::is_sorted(answers->begin(), answers->end(), by_id)) {
    std::stable_sort(answers->begin(), answers->end(), by_id);
  }
  for (const auto& entry : *answers) {
    const Tick_Answer& a = entry.second;
    relay_.AddAnswer(entry.first, a);
    for (const Update_Object& u : a.object_updates) {
      sim::UpdateMissionObject(u.mission_id, {u.object_position_x, u.object_position_y}, *world_,
                               missions_);
    }
    for (const Delete_Object& d : a.object_deletes) missions_->erase(d.mission_id);
    if (observe) observe(entry.first, a);
  }
  answers->clear();
}

core::Velocity LockstepEngine::CommandOf(const Tick_Answer& answer) {
  return IsFinite(answer.command) ? ToVelocity(answer.command) : core::Velocity();
}

}  // namespace swarm_transport
