// Shared pieces of the fuzz targets: messages and core values from fuzzed bytes. Floats come
// as any bit pattern (NaN, infinities, huge values included) unless a target asks for a range.
#ifndef SWARM_TRANSPORT_TEST_FUZZ_FUZZ_COMMON_H_
#define SWARM_TRANSPORT_TEST_FUZZ_FUZZ_COMMON_H_

#include <fuzzer/FuzzedDataProvider.h>

#include <cstdint>
#include <cstdlib>
#include <set>

#include "swarm_transport/New_Mission.h"

namespace swarm_transport {
namespace fuzz {

// Fails the run (the fuzzer reports it with the input) when an invariant does not hold.
inline void Require(bool ok) {
  if (!ok) std::abort();
}

inline float AnyFloat(FuzzedDataProvider* in) {
  // Mostly plausible values, sometimes raw bit patterns.
  if (in->ConsumeBool()) return in->ConsumeFloatingPointInRange<float>(-20.0f, 20.0f);
  return in->ConsumeFloatingPoint<float>();
}

inline New_Mission AnyOrder(FuzzedDataProvider* in) {
  New_Mission m;
  m.robot_index_from = in->ConsumeIntegralInRange<std::uint16_t>(0, 40);
  m.robot_index_to = in->ConsumeIntegralInRange<std::uint16_t>(0, 40);
  const std::size_t ids = in->ConsumeIntegralInRange<std::size_t>(0, 6);
  for (std::size_t i = 0; i < ids; ++i) {
    m.robot_ids.push_back(in->ConsumeIntegralInRange<std::uint16_t>(0, 40));
  }
  m.leader_number = in->ConsumeIntegral<std::uint8_t>();
  m.mission_id = in->ConsumeIntegralInRange<std::uint16_t>(0, 5);
  m.object_position_x = AnyFloat(in);
  m.object_position_y = AnyFloat(in);
  m.object_size_x = AnyFloat(in);
  m.object_size_y = AnyFloat(in);
  m.target_x = AnyFloat(in);
  m.target_y = AnyFloat(in);
  m.transport_mode = in->ConsumeIntegralInRange<std::uint8_t>(0, 3);
  m.start_tick = in->ConsumeIntegralInRange<std::uint64_t>(0, 5);
  m.robot_count = in->ConsumeIntegralInRange<std::uint16_t>(0, 30);
  return m;
}

inline std::set<std::uint16_t> KnownRobots(std::uint16_t n) {
  std::set<std::uint16_t> ids;
  for (std::uint16_t i = 0; i < n; ++i) ids.insert(i);
  return ids;
}

}  // namespace fuzz
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_TEST_FUZZ_FUZZ_COMMON_H_
