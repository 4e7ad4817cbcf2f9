// Per-particle power-of-two time steps (paper 4.2; Saitoh & Makino 2009; docs/mudflow.md
// "Time steps").
#include "talus/mudflow/time_levels.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace talus {
namespace {

// The explicit viscous limit dt <= s^2 / (8 nu) (Morris et al. 1997: 0.125 h^2 / nu).
constexpr double kViscousStepFactor = 0.125;

}  // namespace

// Paper 4.2's "Courant condition" in the Galilean-invariant form of SPH (Monaghan 1997): the
// signal a particle must not outrun within its spacing travels at c + w relative to the
// particle, whatever the flow's own speed; the ground limit keeps the particle's path on every
// cell of the bilinear ground it crosses.
double stable_step(double spacing, double wave_speed, double closing, double speed, double acceleration,
                   const StepCriteria& criteria) {
  double step = std::numeric_limits<double>::infinity();
  const double signal = wave_speed + closing;
  if (signal > 0.0) step = spacing / signal;
  if (acceleration > 0.0) step = std::min(step, std::sqrt(spacing / acceleration));
  step *= criteria.courant;
  if (criteria.internal_viscosity > 0.0) {
    step = std::min(step, kViscousStepFactor * spacing * spacing / criteria.internal_viscosity);
  }
  if (criteria.ground_cell > 0.0 && speed > 0.0) {
    step = std::min(step, criteria.cells_per_step * criteria.ground_cell / speed);
  }
  return step;
}

int level_for_step(double step, double coarse_step, int deepest) {
  if (!(step < coarse_step)) return std::isnan(step) ? deepest : 0;
  // ceil(log2(coarse / step)) computed exactly by doubling, so rounding cannot put a step above
  // the criterion.
  int level = 0;
  double level_step = coarse_step;
  while (level < deepest && level_step > step) {
    level_step *= 0.5;
    ++level;
  }
  return level;
}

int aligned_level(int wanted, std::uint64_t tick, int finest_level) {
  int level = wanted;
  while (level < finest_level && tick % ticks_per_step(level, finest_level) != 0) ++level;
  return level;
}

}  // namespace talus
