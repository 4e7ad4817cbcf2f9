// Areal density, depth and basal pressure of the mud columns (paper 4.1; docs/mudflow.md
// "State equation").
#include "talus/mudflow/flow_density.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {

double natural_smoothing_radius(const ParticleSet& particles, std::size_t i) {
  const double sigma = particles.density[i];
  if (!(sigma > 0.0)) return particles.radius[i];
  return kSupportPerSpacing * std::sqrt(particles.mass[i] / sigma);
}

double smoothing_radius(const ParticleSet& particles, std::size_t i, double smallest) {
  const double radius = particles.radius[i];
  return std::clamp(natural_smoothing_radius(particles, i), std::min(radius, smallest),
                    kLargestSmoothingGrowth * radius);
}

// The pairs in the search's order, in two loops: the kernels of every pair, in one loop the
// compiler vectorises (slot arrays read directly), then the sum in that order, so sigma is the
// same whatever the thread count and with or without vector instructions.
double gather_density(const ParticleSet& particles, const PairSearch& search, std::size_t i, double smoothing,
                      NeighbourList& neighbours) {
  const double xi = particles.x[i], yi = particles.y[i], inverse_i = 1.0 / smoothing;
  const std::span<const std::uint32_t> slots = search.find_pairs(xi, yi, smoothing, static_cast<std::uint32_t>(i));
  const std::size_t count = slots.size();
  neighbours.resize(count);
  thread_local std::vector<double> terms;  // kg/m2: each pair's term of the sum
  if (terms.size() < count) terms.resize(count);
  double* term = terms.data();
  NeighbourPair* pairs = neighbours.data();
  const std::uint32_t* slot_of = slots.data();
  const PairSearch::SlotArrays slot = search.slot_arrays();
  constexpr double kSmallestPositive = std::numeric_limits<double>::denorm_min();
#pragma omp simd
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t s = slot_of[k];
    const double dx = xi - slot.x[s], dy = yi - slot.y[s];
    const double r = std::sqrt(dx * dx + dy * dy);
    const KernelSample own = sample_kernel(r, inverse_i);
    const KernelSample other = sample_kernel(r, slot.inverse_radius[s]);
    term[k] = slot.mass[s] * (0.5 * (own.value + other.value));
    // At r = 0 (two feet on one spot) the gradient is zero by symmetry. The division is done for
    // every pair, by at least the smallest double, so the loop has no branch.
    const double factor = 0.5 * (own.slope + other.slope) / std::max(r, kSmallestPositive);
    pairs[k] = {slot.index[s], static_cast<float>(term[k]), r > 0.0 ? factor : 0.0};
  }
  double sigma = particles.mass[i] * sample_kernel(0.0, inverse_i).value;
  for (std::size_t k = 0; k < count; ++k) sigma += term[k];
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
