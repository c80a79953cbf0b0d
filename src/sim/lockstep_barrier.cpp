#include "swarm_transport/sim/lockstep_barrier.h"

namespace swarm_transport {
namespace sim {

void LockstepBarrier::Add(std::uint16_t id) { robots_[id] = Slot(); }

void LockstepBarrier::Remove(std::uint16_t id) {
  const auto it = robots_.find(id);
  if (it == robots_.end()) return;
  if (it->second.live && !it->second.has_answer && awaiting_ > 0) --awaiting_;
  robots_.erase(it);
}

bool LockstepBarrier::Live(std::uint16_t id) const {
  const auto it = robots_.find(id);
  return it != robots_.end() && it->second.live;
}

void LockstepBarrier::SendsTickDone(std::uint16_t id) {
  const auto it = robots_.find(id);
  if (it != robots_.end()) it->second.sends_tick_done = true;
}

void LockstepBarrier::MakeLive(std::uint16_t id) {
  const auto it = robots_.find(id);
  if (it == robots_.end() || it->second.live) return;
  Slot& slot = it->second;
  slot.live = true;
  slot.answered = slot.asked;
  slot.has_answer = false;
  slot.stale = false;
}

void LockstepBarrier::MakeNotLive(std::uint16_t id) {
  const auto it = robots_.find(id);
  if (it != robots_.end()) it->second.live = false;
}

bool LockstepBarrier::Resynchronise(std::uint16_t id) {
  const auto it = robots_.find(id);
  if (it == robots_.end()) return false;
  Slot& slot = it->second;
  if (!slot.live || slot.has_answer || !slot.stale) return false;
  slot.answered = slot.asked;
  return true;
}

void LockstepBarrier::EndAll() {
  awaiting_ = 0;
  for (auto& entry : robots_) entry.second.live = false;
}

void LockstepBarrier::StartTick(std::uint64_t tick) {
  tick_ = tick;
  awaiting_ = 0;
}

void LockstepBarrier::Ask(std::uint16_t id) {
  const auto it = robots_.find(id);
  if (it == robots_.end() || !it->second.live) return;
  Slot& slot = it->second;
  ++slot.asked;
  slot.has_answer = false;
  slot.done = false;
  slot.stale = false;
  ++awaiting_;
}

LockstepBarrier::Command LockstepBarrier::OnCommand(std::uint16_t id,
                                                    const core::Velocity& velocity) {
  const auto it = robots_.find(id);
  if (it == robots_.end() || !it->second.live) return Command::kOutside;
  Slot& slot = it->second;
  if (slot.answered >= slot.asked) return Command::kUnsolicited;
  ++slot.answered;
  if (slot.answered != slot.asked) {
    slot.stale = true;  // it stood in that tick and the late answer stays ignored
    return Command::kStale;
  }
  slot.answer = velocity;
  slot.has_answer = true;
  if (awaiting_ > 0) --awaiting_;
  return Command::kAnswer;
}

void LockstepBarrier::OnTickDone(std::uint16_t id, const std::string& publisher,
                                 std::uint64_t tick, std::uint64_t events_published) {
  const auto it = robots_.find(id);
  if (it == robots_.end()) return;
  Slot& slot = it->second;
  if (slot.publisher != publisher) {  // first word, or the robot came back in another process
    if (!slot.publisher.empty()) announced_[slot.publisher] -= slot.events_announced;
    slot.publisher = publisher;
    slot.events_announced = 0;
  }
  announced_[publisher] += events_published - slot.events_announced;
  slot.events_announced = events_published;
  slot.sends_tick_done = true;
  if (slot.live && tick == tick_) slot.done = true;
}

void LockstepBarrier::OnRobotMessage(const std::string& publisher) { ++received_[publisher]; }

void LockstepBarrier::Await(const EventKey& event) {
  if (events_seen_.count(event) == 0) events_awaited_.insert(event);
}

void LockstepBarrier::Seen(const EventKey& event) {
  events_seen_.insert(event);
  events_awaited_.erase(event);
}

void LockstepBarrier::Forget(std::uint16_t mission_id) {
  for (auto it = events_awaited_.begin(); it != events_awaited_.end();) {
    it = it->first == mission_id ? events_awaited_.erase(it) : std::next(it);
  }
  for (auto it = events_seen_.begin(); it != events_seen_.end();) {
    it = it->first == mission_id ? events_seen_.erase(it) : std::next(it);
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
  if (orders_due_.erase(mission_id) == 0 && !have_schedule_) orders_early_.insert(mission_id);
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

bool LockstepBarrier::Complete(const Slot& slot) const {
  if (!slot.has_answer) return false;
  if (!slot.sends_tick_done) return true;
  if (!slot.done) return false;
  const auto announced = announced_.find(slot.publisher);
  const auto received = received_.find(slot.publisher);
  const std::uint64_t want = announced == announced_.end() ? 0 : announced->second;
  const std::uint64_t have = received == received_.end() ? 0 : received->second;
  return have >= want;
}

bool LockstepBarrier::AllAnswered() const {
  if (awaiting_ != 0) return false;
  for (const auto& entry : robots_) {
    if (entry.second.live && !Complete(entry.second)) return false;
  }
  return true;
}

std::vector<std::uint16_t> LockstepBarrier::Late() const {
  std::vector<std::uint16_t> late;
  for (const auto& entry : robots_) {
    if (entry.second.live && !Complete(entry.second)) late.push_back(entry.first);
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
