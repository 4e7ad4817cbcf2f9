// Counter-based random numbers (DESIGN.md section 2, "same seed, same layers, whatever the
// thread count"): every draw is a pure function of (seed, source, run, counter), so a
// trajectory's numbers do not depend on which thread runs it or in which order.
#pragma once

#include <cstdint>

namespace talus {

// Stateless 64-bit mix of four words (SplitMix64 finaliser rounds, Steele et al. 2014).
std::uint64_t counter_hash(std::uint64_t seed, std::uint64_t source, std::uint64_t run, std::uint64_t counter);

// A stream of draws for one (seed, source, run); the counter advances by one per draw.
class CounterRandom {
 public:
  CounterRandom(std::uint64_t seed, std::uint64_t source, std::uint64_t run)
      : seed_(seed), source_(source), run_(run) {}
  std::uint64_t next_bits() { return counter_hash(seed_, source_, run_, counter_++); }
  double uniform();                              // [0, 1)
  double uniform(double low, double high);       // [low, high)
  double normal();                               // standard normal (Box-Muller)
  std::uint64_t draws() const { return counter_; }

 private:
  std::uint64_t seed_, source_, run_;
  std::uint64_t counter_ = 0;
};

}  // namespace talus
