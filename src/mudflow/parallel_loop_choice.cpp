// One thread or all for the per-particle loops, from timed trials (docs/mudflow.md "Threads").
#include "talus/mudflow/parallel_loop_choice.hpp"

#include <algorithm>

namespace talus {

ParallelLoopChoice::ParallelLoopChoice(int period) : first_period_(period), period_(period) {}

void ParallelLoopChoice::record(double seconds, std::uint64_t particle_steps) {
  if (first_period_ == 0 || particle_steps == 0) return;
  const double cost = seconds / static_cast<double>(particle_steps);
  if (position_ == 0) {
    one_thread_cost_ = cost;
  } else if (position_ == 1) {
    const bool faster = cost < one_thread_cost_;
    const bool confirmed = decided_ && faster == chosen_parallel_;
    period_ = confirmed ? std::min(2 * period_, kLongestPeriods * first_period_) : first_period_;
    decided_ = true;
    chosen_parallel_ = faster;
  }
  position_ = (position_ + 1) % period_;
}

}  // namespace talus
