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

void LockstepBarrier::StatusRelayed(const core::StatusKey& status) {
  statuses_owed_.insert(status);
}

void LockstepBarrier::OnDispatcherAnswer(const core::DispatcherAnswer& answer) {
  if (answer.has_positions) {
    checked_ = answered_ ? std::max(checked_, answer.checked_tick) : answer.checked_tick;
    answered_ = true;
  }
  hold_from_ = answer.hold_from_tick;
  if (answer.status) {
    const auto it = statuses_owed_.find(*answer.status);
    if (it != statuses_owed_.end()) statuses_owed_.erase(it);
  }
  for (const auto& order : answer.orders) {
    if (orders_early_.erase(order.first) == 0) orders_due_[order.first] = order.second;
  }
  for (const core::Signal& signal : answer.events) {
    const EventKey key{signal.mission_id, static_cast<std::uint8_t>(signal.kind)};
    const auto early = events_early_.find(key);
    if (early != events_early_.end()) {
      events_early_.erase(early);
    } else {
      events_awaited_.insert(key);
    }
  }
}

void LockstepBarrier::OrderArrived(std::uint16_t mission_id) {
  if (orders_due_.erase(mission_id) == 0) orders_early_.insert(mission_id);
}

void LockstepBarrier::EventArrived(const EventKey& event) {
  if (events_awaited_.erase(event) == 0) events_early_.insert(event);
}

void LockstepBarrier::Forget(std::uint16_t mission_id) {
  orders_early_.erase(mission_id);
  for (auto it = events_early_.begin(); it != events_early_.end();) {
    it = it->first == mission_id ? events_early_.erase(it) : std::next(it);
  }
}

bool LockstepBarrier::AnswerDue(std::uint64_t tick) const {
  return tick >= 1 && hold_from_ != 0 && tick >= hold_from_ && (!answered_ || checked_ < tick - 1);
}

bool LockstepBarrier::DispatcherPending(std::uint64_t tick) const {
  if (AnswerDue(tick)) return true;
  if (!statuses_owed_.empty() || !events_awaited_.empty()) return true;
  for (const auto& order : orders_due_) {
    if (order.second <= tick) return true;
  }
  return false;
}

LockstepBarrier::DispatcherWait LockstepBarrier::WaitsFor(std::uint64_t tick) const {
  DispatcherWait wait;
  wait.answer = AnswerDue(tick);
  wait.first = wait.answer && !answered_;
  wait.statuses.assign(statuses_owed_.begin(), statuses_owed_.end());
  wait.events.assign(events_awaited_.begin(), events_awaited_.end());
  for (const auto& order : orders_due_) {
    if (order.second <= tick) wait.orders.push_back(order.first);
  }
  return wait;
}

std::string LockstepBarrier::DispatcherWait::Text(std::uint64_t tick) const {
  std::string text;
  const auto add = [&text](const std::string& what) { text += (text.empty() ? "" : "; ") + what; };
  if (answer) {
    add(first ? std::string("no first answer")
              : "no answer to the positions of tick " + std::to_string(tick - 1));
  }
  for (const core::StatusKey& s : statuses) {
    add("no answer to the " + std::string(core::PhaseName(s.phase)) + " of mission " +
        std::to_string(s.mission_id) + " (tick " + std::to_string(s.tick) + ")");
  }
  for (std::uint16_t id : orders) add("no order of mission " + std::to_string(id));
  for (const EventKey& e : events) {
    add(std::string("no ") +
        (e.second == static_cast<std::uint8_t>(core::MissionEventKind::kLoaded) ? "LOADED"
                                                                                : "UNLOADED") +
        " for mission " + std::to_string(e.first));
  }
  return text;
}

LockstepBarrier::DispatcherWait LockstepBarrier::GiveUpDispatcher(std::uint64_t tick) {
  DispatcherWait given_up = WaitsFor(tick);
  if (given_up.first) {
    hold_from_ = 0;  // no dispatcher answers: not waited for again until one does
  } else if (given_up.answer) {
    checked_ = tick - 1;
  }
  statuses_owed_.clear();
  events_awaited_.clear();
  for (std::uint16_t id : given_up.orders) orders_due_.erase(id);
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
