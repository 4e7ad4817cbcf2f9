// When a mud-flow run will end, for progress that means time (docs/mudflow.md, section 10, "End
// of run"). A run ends at `duration` or when its kinetic energy falls below
// stop_energy_fraction x its peak. After the peak the kinetic energy of a stopping flow decays
// about exponentially, so a least-squares line through ln(kinetic energy) over the last few
// coarse steps says when it will cross the threshold; the expected end is the earlier of that
// time and the duration. The estimate only informs the progress report: it changes nothing in
// the run.
#pragma once

#include <cstddef>
#include <vector>

namespace talus {

class RunEndEstimate {
 public:
  // duration (s): the longest simulated time; stop_energy_fraction (-): the energy criterion.
  RunEndEstimate(double duration, double stop_energy_fraction);

  // The state after a coarse step: simulated time (s), total kinetic energy (J) and the wall time
  // the run has taken so far (s). Times increase from one call to the next.
  void record(double time, double kinetic_energy, double wall_seconds);

  double time() const { return time_; }                  // s: simulated so far
  double expected_end() const { return expected_end_; }  // s: simulated time at the expected end
  // Share of the run done, time over expected end: never decreasing from one record to the next,
  // and below 1 until the run has ended (1 is for the caller to report).
  double fraction_done() const { return fraction_done_; }
  // Wall time (s) the rest should take, at the wall time per simulated second of the last coarse
  // steps.
  double wall_seconds_left() const;

 private:
  // The time ln(kinetic energy) reaches ln(threshold), from the line fitted through the points
  // since the peak (at most kFitPoints), or the duration when the energy is not decaying.
  double energy_end() const;

  struct Point {
    double time, log_energy, wall_seconds;
  };
  double duration_;
  double stop_energy_fraction_;
  std::vector<Point> points_;
  std::size_t peak_ = 0;      // index of the point of peak kinetic energy
  double peak_energy_ = 0;    // J
  double time_ = 0;           // s
  double expected_end_;       // s
  double fraction_done_ = 0;  // -
};

}  // namespace talus
