// Shared pieces of the fission and fusion tests (paper 4.2): a tilted plane, particle radii from
// spacings, brute-force SPH densities and the pair search the adaptivity uses.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "../../validation/synthetic_ground.hpp"
#include "talus/mudflow/pair_search.hpp"
#include "talus/mudflow/particle_set.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus::adaptivity_fixtures {

// A plane z = 500 - 0.2 x + 0.1 y (m) over x in [0, 200] m, y in [-200, 0] m.
inline GroundModel plane_ground() {
  return testing_ground::make_ground(
      testing_ground::local_spec(41, 41, 5.0), [](double x, double y) { return 500.0 - 0.2 * x + 0.1 * y; },
      testing_ground::fast_material(0.0, 0.0, 0.5));
}

inline double radius_of_spacing(double spacing) { return kSupportPerSpacing * spacing; }

// Areal density (kg/m2) of every particle by the symmetrised SPH sum over all particles.
inline void set_sph_density(ParticleSet& particles) {
  for (std::size_t i = 0; i < particles.size(); ++i) {
    double sum = 0;
    for (std::size_t j = 0; j < particles.size(); ++j) {
      const double r = std::hypot(particles.x[i] - particles.x[j], particles.y[i] - particles.y[j]);
      sum += particles.mass[j] * 0.5 * (kernel_value(r, particles.radius[i]) + kernel_value(r, particles.radius[j]));
    }
    particles.density[i] = sum;
  }
}

// The pair search over the particles' support radii, as the adaptivity uses it.
inline PairSearch binned(const ParticleSet& particles) {
  PairSearch search;
  search.rebuild(particles, particles.radius, *std::min_element(particles.radius.begin(), particles.radius.end()));
  return search;
}

}  // namespace talus::adaptivity_fixtures
