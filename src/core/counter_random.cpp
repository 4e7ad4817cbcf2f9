// Counter-based random numbers; see the header for why they are counter-based.
#include "talus/core/counter_random.hpp"

#include <cmath>
#include <numbers>

namespace talus {
namespace {

std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

}  // namespace

std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t source, std::uint64_t run, std::uint64_t counter) {
  std::uint64_t h = splitmix64(seed);
  h = splitmix64(h ^ source);
  h = splitmix64(h ^ run);
  return splitmix64(h ^ counter);
}

double CounterRandom::uniform() {
  return static_cast<double>(next_bits() >> 11) * 0x1.0p-53;  // 53 random mantissa bits
}

double CounterRandom::uniform(double low, double high) { return low + (high - low) * uniform(); }

double CounterRandom::normal() {
  const double u1 = 1.0 - uniform();  // (0, 1]
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

}  // namespace talus
