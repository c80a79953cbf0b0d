// Running figures of one robot's tick timing and perception delivery, for benchmarks.
#ifndef SWARM_TRANSPORT_CORE_TICK_STATS_H_
#define SWARM_TRANSPORT_CORE_TICK_STATS_H_

#include <cstddef>
#include <cstdint>
#include <string>

namespace swarm_transport {
namespace core {

// A tick is late when it starts more than this factor times the period after the previous one.
constexpr double kLateTickFactor = 1.1;

// Counts what a benchmark asks of a robot [issue 5]: ticks, late ticks and the longest period
// (real time), radio rounds received and missed, and how many of the in-range robots' updates
// were delivered within one tick. Times are wall seconds from any fixed origin; the counters
// are cumulative, the maxima cover the time since the last TakeLine().
class TickStats {
 public:
  // `realtime`: ticks follow a wall timer (lateness is measured); otherwise lock-step, where
  // every radio round is a tick and a missed round is a late tick.
  TickStats(double period_s, bool realtime);

  // A radio round `round` sampled at sim time `sim_time_s` arrived at wall time `now_s`;
  // returns its delivery latency (s). Real time: the simulator's sim time is wall time since
  // its start, so the smallest (now - sim_time) seen estimates that start and the latency is
  // the excess over it (a lower bound, exact for the fastest delivery seen). Lock-step: 0 (a
  // round is the tick it starts).
  double OnRound(std::uint64_t round, double sim_time_s, double now_s);
  // Rounds that never arrived just before the latest one.
  std::uint64_t last_gap() const { return last_gap_; }
  // A tick started at wall time `now_s`.
  void OnTick(double now_s);
  // At a tick: `expected` in-range robots, `delivered` of them with a fresh update.
  void CountUpdates(std::size_t expected, std::size_t delivered);
  // "ticks=.. late=.. max_period_ms=.. rounds=.. missed_rounds=.. updates=.. delivered=..
  // max_latency_ms=.. first_tick_wall=.." for a diagnostics line; resets the maxima.
  std::string TakeLine();

  std::uint64_t ticks() const { return ticks_; }
  std::uint64_t late_ticks() const { return late_ticks_; }
  std::uint64_t rounds() const { return rounds_; }
  std::uint64_t missed_rounds() const { return missed_rounds_; }
  std::uint64_t updates() const { return updates_; }
  std::uint64_t delivered() const { return delivered_; }
  double max_period_s() const { return max_period_s_; }
  double max_latency_s() const { return max_latency_s_; }
  double first_tick_s() const { return first_tick_s_; }

 private:
  double period_s_;
  bool realtime_;
  std::uint64_t ticks_ = 0;
  std::uint64_t late_ticks_ = 0;
  std::uint64_t rounds_ = 0;
  std::uint64_t missed_rounds_ = 0;
  std::uint64_t updates_ = 0;
  std::uint64_t delivered_ = 0;
  bool have_round_ = false;
  std::uint64_t last_round_ = 0;
  std::uint64_t last_gap_ = 0;
  double min_offset_s_ = 0.0;  // smallest (arrival wall - sim time) so far
  double last_tick_s_ = -1.0;  // wall time of the previous tick (< 0: none yet)
  double first_tick_s_ = -1.0;
  double max_period_s_ = 0.0;
  double max_latency_s_ = 0.0;
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_TICK_STATS_H_
