// Fusion of particles (paper 4.2, fig. 8b): a group of four flowing particles of one size that
// is calm (low pressure contrast, nearly equal velocities) and compact, its footprint nearly
// round (the eigenvalues of the spread of its positions within a factor of two), merges into one
// particle of twice the spacing at its centre of mass, with its total mass and momentum: both
// conserved exactly up to rounding. Sizes stay bounded by largest_spacing.
#pragma once

#include <cstddef>

#include "talus/ground/ground_model.hpp"
#include "talus/mudflow/pair_search.hpp"
#include "talus/mudflow/particle_set.hpp"

namespace talus {

struct FusionRule {
  double threshold = 0.1;         // every member's pressure_contrast below this (-)
  double speed_difference = 0.5;  // members' velocities within this of the group's mean (m/s)
  double largest_spacing = 10;    // m: merged particles never exceed this spacing
  // Crowded fusion (docs/mudflow.md section 8), off at 0: a group is crowded when twice each
  // member's natural_smoothing_radius, the radius the merged particle would sum over, is at
  // most crowded_radius (m). A crowded group merges when its members' pressure_contrast is below
  // crowded_threshold (-) and their velocities are within the larger of speed_difference and
  // kCrowdedSpeedFraction of the group's speed of its mean velocity.
  double crowded_radius = 0;
  double crowded_threshold = 0.25;
};

// Crowded groups: members' velocities within this fraction of the group's speed (-).
inline constexpr double kCrowdedSpeedFraction = 0.1;

// Merges calm groups, chosen greedily in index order on the state at the call (each particle in
// one group at most; the group of i is i and its three nearest flowing neighbours of the same
// radius not yet in a group, ties by index). A group merges when every member's
// pressure_contrast is below the threshold and its velocity within speed_difference of the
// group's mass-weighted mean, the eigenvalues of the mass-weighted spread of the members'
// horizontal positions are within a factor of two of each other, every member is within one
// spacing of the centre of mass, and the merged spacing stays within largest_spacing. The merged
// particle has the group's mass, its centre of mass (z from the ground model), its momentum
// divided by its mass, twice the support radius, the smallest level and still time, and the
// mass-weighted mean acceleration, density, depth and pressure (until the caller recomputes
// them). It takes the place of the group's lowest index; the others are removed. `search` holds
// the particles as they are at the call, with their support radii; the caller rebuilds it
// afterwards. A crowded group (rule.crowded_radius) passes with its own contrast threshold and
// speed tolerance instead of the calm ones. Returns the number of merges.
std::size_t merge_particles(ParticleSet& particles, const PairSearch& search, const GroundModel& ground,
                            const FusionRule& rule);

}  // namespace talus
