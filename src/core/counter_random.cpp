// Counter-based random numbers; see the header for why they are counter-based.
#include "talus/core/counter_random.hpp"

#include <cmath>
#include <numbers>

namespace talus {

std::uint64_t stream_key(std::uint64_t seed, std::uint64_t source, std::uint64_t run) {
  std::uint64_t h = splitmix64(seed);
  h = splitmix64(h ^ source);
  return splitmix64(h ^ run);
}

std::uint64_t stream_key(std::uint64_t seed, std::uint64_t source, std::uint64_t run, std::uint64_t draw) {
  const std::uint64_t key = stream_key(seed, source, run);
  return draw == 0 ? key : splitmix64(key ^ splitmix64(draw));
}

std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t source, std::uint64_t run, std::uint64_t counter) {
  return splitmix64(stream_key(seed, source, run) ^ counter);
}

double CounterRandom::normal() {
  const double u1 = 1.0 - uniform();  // (0, 1]
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace talus
