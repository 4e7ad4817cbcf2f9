// The state of each mud column from its neighbours (paper 4.1, state equation (1) applied through
// the column; docs/mudflow.md "State equation"): the SPH sum of the masses over the horizontal
// plane is the column's areal density sigma (kg/m2), its flow thickness normal to the ground is
// h = sigma cos(theta) / rho0 and its basal pressure P = rho0 g cos(theta) h (the stiff limit of
// P = k (rho - rho0) integrated over the depth is hydrostatic).
//
// Smoothing radius. A column alone has the depth of its own kernel, m W(0, R) / rho0 = 0.39 of the
// depth it was created with (R = 2.4 spacings), whatever the resolution: with a fixed radius a
// thinning front cannot get thinner than that, moves as a bore and lags (shallow-water SPH uses
// a radius that follows the density: Rodriguez-Paz & Bonet 2005, Vacondio et al. 2012). So each
// particle sums with a smoothing radius R_s = 2.4 sqrt(m / sigma) from its latest density (its
// spacing), never below its size's support radius R and at most kLargestSmoothingGrowth R. With
// crowded fusion (particle_fusion.hpp) the lower bound is the finest particles' support radius
// instead, so a coarse particle in deep mud sums over the radius its density asks for.
//
// Pairs. i and j interact when r < max(R_s,i, R_s,j), with the kernel averaged over both radii,
// W_ij = (W(r, R_s,i) + W(r, R_s,j)) / 2, so pair forces are equal and opposite. PairSearch finds
// every pair of a particle, the ones only the wider neighbour reaches included.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>
#include <vector>

#include "talus/mudflow/pair_search.hpp"
#include "talus/mudflow/particle_set.hpp"

namespace talus {

// R_s <= this x R: a column can thin to 0.39 / 4^2 = 2.4% of its creation depth (-).
inline constexpr double kLargestSmoothingGrowth = 4.0;

// One neighbour j of a particle i, with the pair's kernel gradient factor so the force pass
// need not evaluate the kernel again: grad_i W_ij = gradient_factor x (x_i - x_j, y_i - y_j).
struct NeighbourPair {
  std::uint32_t index = 0;
  float weight = 0;            // m_j (W(r, R_s,i) + W(r, R_s,j)) / 2 (kg/m2): the pair's term of sigma_i
  double gradient_factor = 0;  // (dW/dr(r, R_s,i) + dW/dr(r, R_s,j)) / (2 r) (1/m4), <= 0
};
using NeighbourList = std::vector<NeighbourPair>;

struct ColumnConstants {
  double mud_density = 2000;  // rho0 (kg/m3)
  double gravity = 9.81;      // m/s2
};

// 2.4 sqrt(m / sigma) (m): the radius over which particle i would sum about 18 neighbours at its
// latest density, before any bound; R where it has no density yet.
double natural_smoothing_radius(const ParticleSet& particles, std::size_t i);

// R_s (m) of particle i: natural_smoothing_radius within [min(R, smallest), kLargestSmoothingGrowth
// R]. `smallest` (m) is the least radius any particle may sum over: infinite keeps each particle
// at its own size's R at least (the default); crowded fusion passes the finest particles' R.
double smoothing_radius(const ParticleSet& particles, std::size_t i,
                        double smallest = std::numeric_limits<double>::infinity());

// The SPH sum of particle i, of smoothing radius `smoothing` R_s,i (m), over its pairs, its own
// term m_i W(0, R_s,i) included: lists the pairs (i excluded) in the search's order and returns
// sigma (kg/m2). `search` must hold the positions, masses and smoothing radii of this evaluation.
double gather_density(const ParticleSet& particles, const PairSearch& search, std::size_t i, double smoothing,
                      NeighbourList& neighbours);

// Sets i's density, depth h = sigma cos(theta) / rho0 and basal pressure rho0 g cos(theta) h from
// its sum sigma and cos_slope = cos(theta) at its foot.
void set_column_state(ParticleSet& particles, std::size_t i, double sigma, double cos_slope,
                      const ColumnConstants& constants);

}  // namespace talus
