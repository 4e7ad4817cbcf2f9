// The stability guard of the mud flow (issue 5 Deliver 4, as for rock fall; docs/mudflow.md
// "Guard"): a coarse step fails when any particle holds a value that is not a number, or when
// the flow's mechanical energy grew by more than the sources can explain. Without friction the
// shallow-flow SPH conserves the energy sum over the columns of
//   m (|u|^2 / 2 + g (z - z_ref) + g cos(theta) h / 2)
// (kinetic, potential of the foot, and the column's own potential: the internal energy of the
// depth-integrated pressure Pi = K sigma^2, whose gradient is the pressure force); friction only
// removes energy, so growth is a numerical failure.
#pragma once

#include "talus/mudflow/particle_set.hpp"
#include "talus/mudflow/surface_following.hpp"

namespace talus {

struct FlowEnergy {
  double kinetic = 0;    // J
  double potential = 0;  // J: m g (z - z_ref)
  double internal = 0;   // J: m g cos(theta) h / 2
  double total() const { return kinetic + potential + internal; }
};

// The energy of every particle (flowing and deposited), summed in index order (J).
FlowEnergy flow_energy(const ParticleSet& particles, const FootNormals& normals, double gravity,
                       double reference_elevation);

// True when every position, velocity and density is a finite number.
bool all_finite(const ParticleSet& particles);

// Energy growth (J) a healthy coarse step never exceeds, as a fraction of the kinetic plus internal
// energy at its start: leapfrog's energy error stays orders of magnitude below it at the Courant
// numbers used, while an unstable step grows the energy geometrically.
inline constexpr double kEnergyGrowthTolerance = 0.01;

// True when the coarse step from `before` to `after` gained more than kEnergyGrowthTolerance x
// (kinetic + internal energy before) beyond `source` (J, the energy brought by entrained mass).
bool energy_blew_up(const FlowEnergy& before, const FlowEnergy& after, double source);

}  // namespace talus
