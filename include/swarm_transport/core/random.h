// The one seeded random generator of a robot: all of its randomness comes from here.
#ifndef SWARM_TRANSPORT_CORE_RANDOM_H_
#define SWARM_TRANSPORT_CORE_RANDOM_H_

#include <cstdint>

namespace swarm_transport {
namespace core {

// splitmix64-seeded xoshiro256** generator: the same (seed, stream) gives the same sequence
// on every platform and standard library.
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream);
  std::uint64_t Next();
  // Uniform in [lo, hi).
  double Uniform(double lo, double hi);

 private:
  std::uint64_t s_[4];
};

}  // namespace core
}  // namespace swarm_transport

#endif  // SWARM_TRANSPORT_CORE_RANDOM_H_
