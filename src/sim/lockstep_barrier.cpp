#include "swarm_transport/sim/lockstep_barrier.h"

#include <algorithm>

namespace swarm_transport {
namespace sim {

void LockstepBarrier::Add(std::uint16_t id) { robots_[id] = Slot(); }

void LockstepBarrier::Remove(std::uint16_t id) {
  const auto it = robots_.find(id);
  if (it == robots_.end()) return;
  if (it->second.live && it->second.asked && !it->second.has_answer && awaiting_ > 0) {
    --awaiting_;
  }
  robots_.erase(it);
}

bool LockstepBarrier::Live(std::uint16_t id) const {
  const auto it = robots_.find(id);
  return it != robots_.end() && it->second.live;
}

void LockstepBarrier::MakeLive(std::uint16_t id) {
  const auto it = robots_.find(id);
  if (it == robots_.end() || it->second.live) return;
  it->second = Slot();
  it->second.live = true;
}

void LockstepBarrier::MakeNotLive(std::uint16_t id) {
  const auto it = robots_.find(id);
  if (it == robots_.end() || !it->second.live) return;
  if (it->second.asked && !it->second.has_answer && awaiting_ > 0) --awaiting_;
  it->second = Slot();
}

void LockstepBarrier::EndAll() {
  awaiting_ = 0;
  for (auto& entry : robots_) entry.second = Slot();
}

void LockstepBarrier::StartTick(std::uint64_t tick) {
  tick_ = tick;
  awaiting_ = 0;
  for (auto& entry : robots_) {
    entry.second.asked = false;
    entry.second.has_answer = false;
  }
}

void LockstepBarrier::Ask(std::uint16_t id) {
  const auto it = robots_.find(id);
  if (it == robots_.end() || !it->second.live || it->second.asked) return;
  it->second.asked = true;
  ++awaiting_;
}

LockstepBarrier::Answer LockstepBarrier::OnAnswer(std::uint16_t id, std::uint64_t tick,
                                                  const core::Velocity& velocity) {
  const auto it = robots_.find(id);
  if (it == robots_.end() || !it->second.live) return Answer::kOutside;
  Slot& slot = it->second;
  if (tick < tick_) return Answer::kStale;
  if (tick > tick_ || !slot.asked || slot.has_answer) return Answer::kUnsolicited;
  slot.answer = velocity;
  slot.has_answer = true;
  if (awaiting_ > 0) --awaiting_;
  return Answer::kAnswer;
}

void LockstepBarrier::Await(const EventKey& event) {
  if (events_seen_.count(event) == 0) events_awaited_.insert(event);
}

void LockstepBarrier::Seen(const EventKey& event) {
  events_seen_.insert(event);
  events_awaited_.erase(event);
}

void LockstepBarrier::Forget(std::uint16_t mission_id) {
  orders_early_.erase(mission_id);
  for (auto it = events_awaited_.begin(); it != events_awaited_.end();) {
    it = it->first == mission_id ? events_awaited_.erase(it) : std::next(it);
  }
  for (auto it = events_seen_.begin(); it != events_seen_.end();) {
    it = it->first == mission_id ? events_seen_.erase(it) : std::next(it);
  }
}

void LockstepBarrier::OnPhase(std::uint16_t mission_id, core::MissionPhase phase, bool loaded_auto,
                              bool unloaded_auto) {
  using core::MissionEventKind;
  using core::MissionPhase;
  switch (phase) {
    case MissionPhase::kLoading:
      if (loaded_auto) Await({mission_id, static_cast<std::uint8_t>(MissionEventKind::kLoaded)});
      break;
    case MissionPhase::kUnloading:
      if (unloaded_auto) {
        Await({mission_id, static_cast<std::uint8_t>(MissionEventKind::kUnloaded)});
      }
      break;
    case MissionPhase::kDone:
    case MissionPhase::kAborted:
    case MissionPhase::kRejected:
      // The id may be used again by a later mission.
      Forget(mission_id);
      break;
    default:
      break;
  }
}

std::vector<LockstepBarrier::EventKey> LockstepBarrier::GiveUpEvents() {
  std::vector<EventKey> given_up(events_awaited_.begin(), events_awaited_.end());
  for (const EventKey& event : given_up) events_seen_.insert(event);
  events_awaited_.clear();
  return given_up;
}

void LockstepBarrier::OnSchedule(
    const std::vector<std::pair<std::uint16_t, std::uint64_t>>& orders) {
  have_schedule_ = true;
  for (const auto& order : orders) {
    if (orders_early_.erase(order.first) == 0) orders_due_[order.first] = order.second;
  }
}

void LockstepBarrier::OrderArrived(std::uint16_t mission_id) {
  // Not due (yet): a later schedule may name it (a recruit's order and the schedule naming it
  // travel on two topics, in either order).
  if (orders_due_.erase(mission_id) == 0) orders_early_.insert(mission_id);
}

void LockstepBarrier::OnRecruits(
    std::uint64_t checked_tick,
    const std::vector<std::pair<std::uint16_t, std::uint64_t>>& recruiting) {
  recruit_checked_ = std::max(recruit_checked_, checked_tick);
  recruits_.clear();
  for (const auto& r : recruiting) recruits_[r.first] = r.second;
}

bool LockstepBarrier::RecruitsUnchecked(std::uint64_t tick) const {
  if (tick == 0) return false;
  for (const auto& r : recruits_) {
    if (r.second < tick && recruit_checked_ < tick - 1) return true;
  }
  return false;
}

void LockstepBarrier::GiveUpRecruits(std::uint64_t tick) {
  if (tick >= 1) recruit_checked_ = std::max(recruit_checked_, tick - 1);
}

bool LockstepBarrier::OrdersMissing(std::uint64_t tick) const {
  if (tick >= 1 && ScheduleMissing()) return true;
  for (const auto& order : orders_due_) {
    if (order.second <= tick) return true;
  }
  return false;
}

std::vector<std::uint16_t> LockstepBarrier::GiveUpOrders(std::uint64_t tick) {
  if (tick >= 1) have_schedule_ = true;
  std::vector<std::uint16_t> given_up;
  for (auto it = orders_due_.begin(); it != orders_due_.end();) {
    if (it->second <= tick) {
      given_up.push_back(it->first);
      it = orders_due_.erase(it);
    } else {
      ++it;
    }
  }
  return given_up;
}

std::vector<std::uint16_t> LockstepBarrier::Late() const {
  std::vector<std::uint16_t> late;
  for (const auto& entry : robots_) {
    const Slot& slot = entry.second;
    if (slot.live && slot.asked && !slot.has_answer) late.push_back(entry.first);
  }
  return late;
}

std::size_t LockstepBarrier::LiveCount() const {
  std::size_t live = 0;
  for (const auto& entry : robots_) live += entry.second.live ? 1 : 0;
  return live;
}

core::Velocity LockstepBarrier::CommandOf(std::uint16_t id) const {
  const auto it = robots_.find(id);
  if (it == robots_.end() || !it->second.has_answer) return core::Velocity();
  return it->second.answer;
}

}  // namespace sim
}  // namespace swarm_transport
