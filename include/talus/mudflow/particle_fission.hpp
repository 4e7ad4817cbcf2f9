// Fission of a particle (paper 4.2, fig. 8a): where a particle's pressure difference with its
// neighbours, relative to its size, exceeds a threshold, it splits into four particles of half
// its spacing, at the centres of the four quarters of its square footprint, each with a quarter
// of its mass and its velocity: mass and momentum are conserved exactly.
#pragma once

#include <cstddef>
#include <vector>

#include "talus/ground/ground_model.hpp"
#include "talus/mudflow/pair_search.hpp"
#include "talus/mudflow/particle_set.hpp"

namespace talus {

// size x |grad P| / P of particle i (-): its basal pressure's relative change across one
// particle size (spacing = radius / kSupportPerSpacing), the gradient taken by the SPH
// difference form sum_j (m_j / sigma_j) (P_j - P_i) grad W_ij over its neighbours in the
// horizontal plane, with the symmetrised kernel W_ij = (W(r, R_i) + W(r, R_j)) / 2, normalised
// so that it is exact for a linear pressure field (Bonet & Lok 1999; the plain sum where the
// neighbours are too few or in a line). Uses the density (kg/m2) and pressure (Pa) fields as
// stored; `search` must hold the particles as they are, with their support radii R. 0 where P
// is 0.
double pressure_contrast(const ParticleSet& particles, const PairSearch& search, std::size_t i);
// pressure_contrast of every flowing particle (0 for the others), computed in parallel, each
// particle writing only its own slot.
std::vector<double> pressure_contrasts(const ParticleSet& particles, const PairSearch& search);

struct FissionRule {
  double threshold = 0.5;        // split when pressure_contrast exceeds this (-)
  double smallest_spacing = 2.5; // m: the finest spacing; no split makes children finer than this
  // m: with crowded fusion, the least smoothing radius (the finest particles' support radius): a
  // particle whose natural_smoothing_radius is at most this does not split, as its children
  // would all sum over this same radius and resolve nothing finer; 0: no such particle.
  double smoothing_floor = 0;
};

// Splits every flowing particle that the rule selects (decided on the state before any split,
// applied in index order; children are appended, the parent becomes the first child). A
// particle of spacing s splits into children of spacing s / 2 and support radius R / 2 at
// (x +- s / 4, y +- s / 4), each of mass m / 4 (exact in binary floating point). Children stand
// on the ground (z from the ground model) and keep the parent's velocity, acceleration, density,
// depth, pressure, level and still time; a particle whose children would leave the ground
// model's valid area, or that the rule's smoothing floor holds, does not split. `search` holds
// the particles as they are at the call, with their support radii; the caller rebuilds it
// afterwards. Returns the number of particles split.
std::size_t split_particles(ParticleSet& particles, const PairSearch& search, const GroundModel& ground,
                            const FissionRule& rule);

}  // namespace talus
