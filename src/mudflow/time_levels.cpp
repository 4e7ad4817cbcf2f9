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

double closing_speed(const ParticleSet& particles, std::size_t i, const NeighbourList& neighbours) {
  const double xi = particles.x[i], yi = particles.y[i];
  const double vxi = particles.vx[i], vyi = particles.vy[i];
  const double* x = particles.x.data();
  const double* y = particles.y.data();
  const double* vx = particles.vx.data();
  const double* vy = particles.vy.data();
  double fastest = 0.0;
  for (const NeighbourPair& pair : neighbours) {
    const std::size_t j = pair.index;
    const double dx = xi - x[j], dy = yi - y[j];
    const double distance = std::sqrt(dx * dx + dy * dy);
    if (!(distance > 0.0)) continue;
    const double approach = -((vxi - vx[j]) * dx + (vyi - vy[j]) * dy) / distance;
    fastest = std::max(fastest, approach);
  }
  return fastest;
}

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
