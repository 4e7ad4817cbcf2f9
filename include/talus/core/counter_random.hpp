// Counter-based random numbers (docs/architecture.md section 8, "same seed, same layers, whatever the
// thread count"): every draw is a pure function of (seed, source, run, counter), so a
// trajectory's numbers do not depend on which thread runs it or in which order.
#pragma once

#include <cstdint>

namespace talus {

// One SplitMix64 round (Steele et al. 2014): a bijective 64-bit mix.
inline std::uint64_t splitmix64(std::uint64_t z) {
  z += 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  return z ^ (z >> 31);
}

// The key of the stream (seed, source, run): the first three of counter_hash's four rounds.
std::uint64_t stream_key(std::uint64_t seed, std::uint64_t source, std::uint64_t run);

// Stateless 64-bit mix of four words: splitmix64(stream_key(seed, source, run) ^ counter).
std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t source, std::uint64_t run, std::uint64_t counter);

// The key of a fresh stream of the same run (seed, source, run): `draw` 0 is stream_key's, each
// later one a new key, for a run drawn again after a numerical failure (docs/rockfall-full.md,
// section 5, "Recovery").
std::uint64_t stream_key(std::uint64_t seed, std::uint64_t source, std::uint64_t run, std::uint64_t draw);

// A stream of draws for one (seed, source, run), and its later draws; the counter advances by one
// per draw.
class CounterRandom {
 public:
  CounterRandom(std::uint64_t seed, std::uint64_t source, std::uint64_t run, std::uint64_t draw = 0)
      : key_(stream_key(seed, source, run, draw)) {}
  // counter_hash(seed, source, run, counter), with the stream's key computed once.
  std::uint64_t next_bits() { return splitmix64(key_ ^ counter_++); }
  // [0, 1): the top 53 bits as the mantissa.
  double uniform() { return static_cast<double>(next_bits() >> 11) * 0x1.0p-53; }
  // [low, high)
  double uniform(double low, double high) { return low + (high - low) * uniform(); }
  double normal();                               // standard normal (Box-Muller)
  std::uint64_t draws() const { return counter_; }

 private:
  std::uint64_t key_;
  std::uint64_t counter_ = 0;
};

}  // namespace talus
