// Whether the mud flow's per-particle loops run on all threads or on one (docs/mudflow.md
// "Threads"). A loop over a few thousand particles lasts well under a millisecond, so a thread
// that waits for a core (another job on the machine) or spins while its partner has lost its core
// can make the parallel loops several times slower than one thread; on an idle machine they are
// up to twice as fast. Neither can be known in advance, so the run measures both: at the start of
// each period of coarse steps it times one coarse step on one thread and one on all threads, and
// runs the rest of the period the faster way, by wall time per particle-step. While the trials
// keep giving the same answer the period doubles, up to kLongestPeriods x the first, so that the
// slower way's trial costs little; a changed answer brings the first period back. The layers are
// the same either way (each loop writes only its own particle's slots): the choice changes the
// speed only.
#pragma once

#include <cstdint>

namespace talus {

class ParallelLoopChoice {
 public:
  // The period grows to at most this many times the first one.
  static constexpr int kLongestPeriods = 8;

  // period: coarse steps from one pair of timed trials to the next (>= 3) at first; 0: always
  // parallel.
  explicit ParallelLoopChoice(int period);

  // The way the next coarse step runs its per-particle loops: true on all threads (the
  // one-thread trial opens a period, the all-thread trial follows it).
  bool parallel() const { return first_period_ == 0 || position_ == 1 || (position_ > 1 && chosen_parallel_); }
  // One coarse step ran the way parallel() said: its wall time (s) and its particle-steps. A step
  // with no particle-step tells nothing and leaves the choice as it is.
  void record(double seconds, std::uint64_t particle_steps);

 private:
  int first_period_;
  int period_;                  // coarse steps in the current period
  int position_ = 0;            // in the period: 0 one-thread trial, 1 all-thread trial, then the faster way
  double one_thread_cost_ = 0;  // s per particle-step in the last one-thread trial
  bool decided_ = false;        // a pair of trials has chosen...
  bool chosen_parallel_ = false;  // ...this way
};

}  // namespace talus
