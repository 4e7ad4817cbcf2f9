// Individual time steps of the particles (paper 4.2, "individual time steps ... from their size
// and from stability criteria such as Courant condition"; docs/mudflow.md "Time steps"): each
// particle's step is the coarse step / 2^level, its level the shallowest whose step meets the
// particle's criteria, at most two levels (a factor 4) above its neighbours' (the limiter of
// Saitoh & Makino 2009), and a particle moves to a longer step only when the current time is a
// multiple of that step, so every step starts and ends on the grid of its level.
#pragma once

#include <cmath>
#include <cstdint>

#include "talus/mudflow/flow_density.hpp"

namespace talus {

// A particle's step may be at most 2^kLimiterLevels times its neighbours' smallest.
inline constexpr int kLimiterLevels = 2;

struct StepCriteria {
  double courant = 0.3;             // C (-)
  double internal_viscosity = 0.5;  // nu (m2/s)
  double ground_cell = 0;           // m: the DEM's smaller cell side (0: no ground criterion)
  double cells_per_step = 0.5;      // a step crosses at most this many DEM cells (-)
};

// How fast a neighbour closes in on a particle (m/s): -(u_i - u_j) . (x_i - x_j) / |x_i - x_j| in
// the horizontal plane of the sums, from dx = x_i - x_j and dv = u_i - u_j; negative when it
// recedes, 0 when the two feet meet. The fastest over the neighbours, at least 0, is w, the
// relative part of the signal speed of Monaghan (1997), which leaves the step independent of the
// flow's own speed; the forces' pass measures it (flow_forces.hpp).
inline double approach_speed(double dx, double dy, double dvx, double dvy) {
  const double distance = std::sqrt(dx * dx + dy * dy);
  if (!(distance > 0.0)) return 0.0;
  return -(dvx * dx + dvy * dy) / distance;
}

// The longest stable step (s) of a particle of spacing s (m) whose shallow-water wave speed is
// c = sqrt(g cos(theta) h) (m/s), neighbours close in at w (m/s), speed is |u| (m/s) and
// acceleration |a| (m/s2): C min(s / (c + w), sqrt(s / |a|)), the explicit viscous limit
// s^2 / (8 nu), and the ground limit cells_per_step x cell / |u|.
double stable_step(double spacing, double wave_speed, double closing, double speed, double acceleration,
                   const StepCriteria& criteria);

// The shallowest level l >= 0 whose step coarse_step / 2^l is at most `step`, at most deepest.
int level_for_step(double step, double coarse_step, int deepest);

// The limiter: a level at least the deepest of the neighbours' levels minus kLimiterLevels.
// neighbour_level(j) gives neighbour j's level, or a negative value for a neighbour to ignore.
template <class NeighbourLevel>
int limited_level(int level, const NeighbourList& neighbours, NeighbourLevel&& neighbour_level) {
  int deepest = -1;
  for (const NeighbourPair& pair : neighbours) {
    const int other = neighbour_level(pair.index);
    if (other > deepest) deepest = other;
  }
  return deepest - kLimiterLevels > level ? deepest - kLimiterLevels : level;
}

// A level for a particle whose step ends at `tick` on a clock of 2^finest_level ticks per coarse
// step: `wanted` where that level's step divides `tick`, else the shallowest deeper level whose
// step does (a particle moves to a longer step only at a time that is a multiple of it).
int aligned_level(int wanted, std::uint64_t tick, int finest_level);

// Ticks in one step of `level` on a clock of 2^finest_level ticks per coarse step.
inline std::uint64_t ticks_per_step(int level, int finest_level) {
  return std::uint64_t{1} << static_cast<unsigned>(finest_level - level);
}

}  // namespace talus
