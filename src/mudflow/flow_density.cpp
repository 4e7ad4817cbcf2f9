// Areal density, depth and basal pressure of the mud columns (paper 4.1; docs/mudflow.md
// "State equation").
#include "talus/mudflow/flow_density.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {
namespace {

// The Wendland C2 kernel of smoothing_kernel.hpp, value and slope together and inline, from the
// inverse support radius 1/R (1/m): this is the innermost loop of the simulation, and the
// out-of-line kernel_value / kernel_slope cost a call and a division each
// (tests/unit/mudflow/flow_density_test.cpp checks that both agree).
struct KernelSample {
  double value;  // W(r, R) (1/m2)
  double slope;  // dW/dr (1/m3)
};
inline KernelSample sample_kernel(double r, double inverse) {
  const double q = r * inverse;
  if (q >= 1.0) return {0.0, 0.0};
  const double u = 1.0 - q;
  const double u3 = u * u * u;
  const double scale = 7.0 / std::numbers::pi * inverse * inverse;  // 1/m2
  return {scale * u3 * u * (1.0 + 4.0 * q), -20.0 * scale * inverse * q * u3};
}

// The pair's kernel value (1/m2) and gradient factor (1/m4), averaged over both radii.
struct PairKernel {
  double value, gradient_factor;
};
inline PairKernel pair_kernel(double r, double inverse_i, double inverse_j) {
  const KernelSample a = sample_kernel(r, inverse_i);
  const KernelSample b = inverse_j == inverse_i ? a : sample_kernel(r, inverse_j);
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

double gather_density(const ParticleSet& particles, const NeighbourGrid& grid, std::size_t i,
                      const std::vector<double>& smoothing, const std::vector<char>& searching,
                      NeighbourList& neighbours, std::vector<HandedPair>& handed) {
  handed.clear();
  const double xi = particles.x[i], yi = particles.y[i], ri = smoothing[i], inverse_i = 1.0 / ri;
  const double* x = particles.x.data();
  const double* y = particles.y.data();
  const double* radius = smoothing.data();
  const double* mass = particles.mass.data();
  const double bin = grid.bin_size();
  const double reach = std::max(ri, bin);
  const double reach2 = reach * reach;
  double sigma = mass[i] * sample_kernel(0.0, inverse_i).value;
  // Two passes: the candidates are filtered without branches first (about half of them lie
  // beyond the support, a branch the processor cannot predict), then the pairs are summed.
  thread_local std::vector<std::uint32_t> candidates;
  candidates.clear();
  grid.for_each_candidate(xi, yi, reach, [&](std::uint32_t j) { candidates.push_back(j); });
  std::size_t count = 0;
  for (const std::uint32_t j : candidates) {
    const double dx = xi - x[j], dy = yi - y[j];
    const double r2 = dx * dx + dy * dy;
    const double support = std::max(ri, radius[j]);
    candidates[count] = j;
    count += static_cast<std::size_t>((r2 < reach2) & (r2 < support * support) & (j != i));
  }
  neighbours.resize(count);
  for (std::size_t k = 0; k < count; ++k) {
    const std::uint32_t j = candidates[k];
    const double dx = xi - x[j], dy = yi - y[j];
    const double r = std::sqrt(dx * dx + dy * dy);
    const double rj = radius[j];
    const PairKernel kernel = pair_kernel(r, inverse_i, rj == ri ? inverse_i : 1.0 / rj);
    sigma += mass[j] * kernel.value;
    neighbours[k] = {j, kernel.gradient_factor};
    if (r >= bin && r >= rj && searching[j] != 0) handed.push_back({j, kernel.value, kernel.gradient_factor});
  }
  return sigma;
}

void add_handed_pairs(const ParticleSet& particles, const std::vector<std::uint32_t>& list,
                      const std::vector<std::vector<HandedPair>>& handed, std::vector<NeighbourList>& neighbours,
                      std::vector<double>& sigma) {
  for (const std::uint32_t i : list) {
    for (const HandedPair& pair : handed[i]) {
      sigma[pair.index] += particles.mass[i] * pair.kernel;
      neighbours[pair.index].push_back({i, pair.gradient_factor});
    }
  }
}

void set_column_state(ParticleSet& particles, std::size_t i, double sigma, double cos_slope,
                      const ColumnConstants& constants) {
  const double depth = sigma * cos_slope / constants.mud_density;
  particles.density[i] = sigma;
  particles.depth[i] = depth;
  particles.pressure[i] = constants.mud_density * constants.gravity * cos_slope * depth;
}

}  // namespace talus
