// Areal density, depth and basal pressure of the mud columns (paper 4.1; docs/mudflow.md
// "State equation").
#include "talus/mudflow/flow_density.hpp"

#include <algorithm>
#include <cmath>

#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {
namespace {

// The pair's kernel value (1/m2) and gradient factor (1/m4), averaged over both radii.
struct PairKernel {
  double value, gradient_factor;
};
inline PairKernel pair_kernel(double r, double inverse_i, double inverse_j) {
  const KernelSample a = sample_kernel(r, inverse_i);
  const KernelSample b = sample_kernel(r, inverse_j);
  // At r = 0 (two feet on one spot) the gradient is zero by symmetry.
  return {0.5 * (a.value + b.value), r > 0.0 ? 0.5 * (a.slope + b.slope) / r : 0.0};
}

}  // namespace

double smoothing_radius(const ParticleSet& particles, std::size_t i) {
  const double radius = particles.radius[i];
  const double sigma = particles.density[i];
  if (!(sigma > 0.0)) return radius;
  const double spread = kSupportPerSpacing * std::sqrt(particles.mass[i] / sigma);
  return std::clamp(spread, radius, kLargestSmoothingGrowth * radius);
}

double gather_density(const ParticleSet& particles, const PairSearch& search, std::size_t i, double smoothing,
                      NeighbourList& neighbours) {
  const double xi = particles.x[i], yi = particles.y[i], ri = smoothing, inverse_i = 1.0 / ri;
  double sigma = particles.mass[i] * sample_kernel(0.0, inverse_i).value;
  thread_local std::vector<std::uint32_t> slots;
  search.find_pairs(xi, yi, ri, static_cast<std::uint32_t>(i), slots);
  neighbours.resize(slots.size());
  for (std::size_t k = 0; k < slots.size(); ++k) {
    const std::uint32_t s = slots[k];
    const double dx = xi - search.x(s), dy = yi - search.y(s);
    const double r = std::sqrt(dx * dx + dy * dy);
    const double inverse_j = search.inverse_radius(s);
    const PairKernel kernel = pair_kernel(r, inverse_i, inverse_j);
    sigma += search.mass(s) * kernel.value;
    neighbours[k] = {search.index(s), kernel.gradient_factor};
  }
  return sigma;
}

void set_column_state(ParticleSet& particles, std::size_t i, double sigma, double cos_slope,
                      const ColumnConstants& constants) {
  const double depth = sigma * cos_slope / constants.mud_density;
  particles.density[i] = sigma;
  particles.depth[i] = depth;
  particles.pressure[i] = constants.mud_density * constants.gravity * cos_slope * depth;
}

}  // namespace talus
