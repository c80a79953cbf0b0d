#include "swarm_transport/core/random.h"

namespace swarm_transport {
namespace core {
namespace {

// 2^64 / golden ratio: spreads consecutive stream numbers over the whole seed space.
constexpr std::uint64_t kGolden = 0x9E3779B97F4A7C15ULL;

std::uint64_t SplitMix64(std::uint64_t* state) {
  std::uint64_t z = (*state += kGolden);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

std::uint64_t RotateLeft(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

}  // namespace

Rng::Rng(std::uint64_t seed, std::uint64_t stream) {
  // xoshiro must not be seeded with correlated words; splitmix64 decorrelates them and never
  // yields an all-zero state.
  std::uint64_t state = seed ^ (stream * kGolden);
  for (std::uint64_t& word : s_) word = SplitMix64(&state);
}

std::uint64_t Rng::Next() {
  const std::uint64_t result = RotateLeft(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = RotateLeft(s_[3], 45);
  return result;
}

double Rng::Uniform(double lo, double hi) {
  // The top 53 bits fill a double's mantissa exactly: uniform in [0, 1) on every platform.
  return lo + (hi - lo) * (static_cast<double>(Next() >> 11) * 0x1.0p-53);
}

}  // namespace core
}  // namespace swarm_transport
