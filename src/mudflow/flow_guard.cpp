// Blow-up detection of the mud flow (issue 5 Deliver 4; docs/mudflow.md "Guard").
#include "talus/mudflow/flow_guard.hpp"

#include <cmath>

namespace talus {

FlowEnergy flow_energy(const ParticleSet& particles, const FootNormals& normals, double gravity,
                       double reference_elevation) {
  FlowEnergy energy;
  for (std::size_t i = 0; i < particles.size(); ++i) {
    const double m = particles.mass[i];
    energy.kinetic += 0.5 * m * particles.velocity(i).squaredNorm();
    energy.potential += m * gravity * (particles.z[i] - reference_elevation);
    energy.internal += 0.5 * m * gravity * normals.z[i] * particles.depth[i];
  }
  return energy;
}

bool all_finite(const ParticleSet& particles) {
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!std::isfinite(particles.x[i] + particles.y[i] + particles.z[i] + particles.vx[i] + particles.vy[i] +
                       particles.vz[i] + particles.density[i])) {
      return false;
    }
  }
  return true;
}

bool energy_blew_up(const FlowEnergy& before, const FlowEnergy& after, double source) {
  const double allowed = kEnergyGrowthTolerance * (before.kinetic + before.internal);
  return !(after.total() - before.total() - source <= allowed);
}

}  // namespace talus
