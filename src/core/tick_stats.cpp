#include "swarm_transport/core/tick_stats.h"

#include <algorithm>
#include <cstdio>

namespace swarm_transport {
namespace core {

TickStats::TickStats(double period_s, bool realtime) : period_s_(period_s), realtime_(realtime) {}

double TickStats::OnRound(std::uint64_t round, double sim_time_s, double now_s) {
  last_gap_ = have_round_ && round > last_round_ + 1 ? round - last_round_ - 1 : 0;
  missed_rounds_ += last_gap_;
  // Lock-step: a round that never arrived is a tick this robot did not answer in time.
  if (!realtime_) late_ticks_ += last_gap_;
  const double offset = now_s - sim_time_s;
  if (!have_round_ || offset < min_offset_s_) min_offset_s_ = offset;
  have_round_ = true;
  last_round_ = round;
  const double latency = realtime_ ? offset - min_offset_s_ : 0.0;
  max_latency_s_ = std::max(max_latency_s_, latency);
  ++rounds_;
  return latency;
}

void TickStats::OnTick(double now_s) {
  if (first_tick_s_ < 0.0) first_tick_s_ = now_s;
  if (realtime_ && last_tick_s_ >= 0.0) {
    const double period = now_s - last_tick_s_;
    max_period_s_ = std::max(max_period_s_, period);
    if (period > kLateTickFactor * period_s_) ++late_ticks_;
  }
  last_tick_s_ = now_s;
  ++ticks_;
}

void TickStats::CountUpdates(std::size_t expected, std::size_t delivered) {
  updates_ += expected;
  delivered_ += std::min(delivered, expected);
}

std::string TickStats::TakeLine() {
  char line[320];
  std::snprintf(
      line, sizeof(line),
      "ticks=%llu late=%llu max_period_ms=%.3f rounds=%llu missed_rounds=%llu "
      "updates=%llu delivered=%llu max_latency_ms=%.3f first_tick_wall=%.6f",
      static_cast<unsigned long long>(ticks_), static_cast<unsigned long long>(late_ticks_),
      max_period_s_ * 1e3, static_cast<unsigned long long>(rounds_),
      static_cast<unsigned long long>(missed_rounds_), static_cast<unsigned long long>(updates_),
      static_cast<unsigned long long>(delivered_), max_latency_s_ * 1e3, first_tick_s_);
  max_period_s_ = 0.0;
  max_latency_s_ = 0.0;
  return line;
}

}  // namespace core
}  // namespace swarm_transport
