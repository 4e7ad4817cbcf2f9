// Fission of particles (paper 4.2, fig. 8a): the pressure-contrast criterion and the 1 -> 4 split.
#include "talus/mudflow/particle_fission.hpp"

#include <array>
#include <cmath>
#include <cstdint>

#include "talus/mudflow/flow_density.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {
namespace {

// Relative tolerance on spacings (-): spacings are particle_size x 2^k up to rounding.
constexpr double kSpacingTolerance = 1e-9;
// Fewer particles than this: the criterion runs on one thread (a parallel region would cost more).
constexpr std::size_t kParallelParticles = 4096;
// det L >= this x (trace L)^2: the eigenvalues of L within a factor of about 10 of each other.
constexpr double kWellConditioned = 0.08;

// Offsets of the four children from their parent, in units of the parent's spacing (paper fig.
// 8a): the centres of the four quarters of the parent's square footprint. The first stays in
// the parent's slot.
constexpr std::array<std::array<double, 2>, 4> kChildOffsets{
    {{-0.25, -0.25}, {0.25, -0.25}, {-0.25, 0.25}, {0.25, 0.25}}};

}  // namespace

// Paper 4.2, splitting criterion: s |grad P| / P, grad P (Pa/m) by the SPH difference form
// G = sum_j (m_j / sigma_j) (P_j - P_i) grad_i W_ij with the symmetrised kernel gradient,
// normalised by the matrix L = sum_j (m_j / sigma_j) grad_i W_ij (x_j - x_i)^T (Bonet & Lok
// 1999) so a linear pressure field gives its exact gradient whatever the neighbours' layout: the
// plain sum underestimates it by 5% inside a square lattice at R = 2.4 spacings, by 21% at its
// edge. Where L is ill-conditioned (no neighbours, or all in a line) the plain sum is used.
double pressure_contrast(const ParticleSet& particles, const PairSearch& search, std::size_t i) {
  const double pressure_i = particles.pressure[i];
  if (!(pressure_i > 0)) return 0;
  const double xi = particles.x[i], yi = particles.y[i], radius_i = particles.radius[i];
  const double inverse_i = 1.0 / radius_i;
  double gradient_x = 0, gradient_y = 0;  // Pa/m: the plain sum G
  double lxx = 0, lxy = 0, lyy = 0;       // -: the normalisation matrix L (symmetric)
  for (const std::uint32_t s : search.find_pairs(xi, yi, radius_i, static_cast<std::uint32_t>(i))) {
    const std::uint32_t j = search.index(s);
    if (!(particles.density[j] > 0)) continue;
    const double dx = xi - search.x(s), dy = yi - search.y(s);
    const double r = std::sqrt(dx * dx + dy * dy);  // m
    if (r == 0) continue;
    const double slope = 0.5 * (sample_kernel(r, inverse_i).slope + sample_kernel(r, search.inverse_radius(s)).slope);
    const double weight = search.mass(s) / particles.density[j] * slope / r;  // 1/m2
    const double difference = particles.pressure[j] - pressure_i;             // Pa
    gradient_x += weight * difference * dx;
    gradient_y += weight * difference * dy;
    lxx -= weight * dx * dx;
    lxy -= weight * dx * dy;
    lyy -= weight * dy * dy;
  }
  const double trace = lxx + lyy, determinant = lxx * lyy - lxy * lxy;
  if (determinant > kWellConditioned * trace * trace) {
    const double corrected_x = (lyy * gradient_x - lxy * gradient_y) / determinant;
    const double corrected_y = (lxx * gradient_y - lxy * gradient_x) / determinant;
    gradient_x = corrected_x;
    gradient_y = corrected_y;
  }
  const double spacing = radius_i / kSupportPerSpacing;  // m
  return spacing * std::hypot(gradient_x, gradient_y) / pressure_i;
}

// Paper 4.2: the criterion of every flowing particle, in parallel (one slot per particle).
std::vector<double> pressure_contrasts(const ParticleSet& particles, const PairSearch& search) {
  const std::size_t n = particles.size();
  std::vector<double> contrast(n, 0.0);
#pragma omp parallel for schedule(static) if (n >= kParallelParticles)
  for (std::size_t i = 0; i < n; ++i) {
    if (particles.state[i] == ParticleState::flowing) contrast[i] = pressure_contrast(particles, search, i);
  }
  return contrast;
}

// Paper 4.2, fig. 8a: every selected parent becomes four children of half its spacing and a
// quarter of its mass each, with its velocity; selection on the state before any split.
std::size_t split_particles(ParticleSet& particles, const PairSearch& search, const GroundModel& ground,
                            const FissionRule& rule) {
  const std::vector<double> contrast = pressure_contrasts(particles, search);
  const std::size_t parents = particles.size();
  std::size_t splits = 0;
  for (std::size_t i = 0; i < parents; ++i) {
    if (particles.state[i] != ParticleState::flowing || !(contrast[i] > rule.threshold)) continue;
    const double spacing = particles.radius[i] / kSupportPerSpacing;  // m
    if (0.5 * spacing < rule.smallest_spacing * (1 - kSpacingTolerance)) continue;
    if (natural_smoothing_radius(particles, i) <= rule.smoothing_floor) continue;
    std::array<std::array<double, 2>, 4> child_xy{};  // m
    bool on_ground = true;
    for (std::size_t c = 0; c < 4; ++c) {
      child_xy[c] = {particles.x[i] + kChildOffsets[c][0] * spacing, particles.y[i] + kChildOffsets[c][1] * spacing};
      on_ground = on_ground && ground.contains(child_xy[c][0], child_xy[c][1]);
    }
    if (!on_ground) continue;

    const double child_mass = 0.25 * particles.mass[i];    // kg, exact
    const double child_radius = 0.5 * particles.radius[i];  // m, exact
    for (std::size_t c = 1; c < 4; ++c) {
      const Eigen::Vector3d foot(child_xy[c][0], child_xy[c][1], ground.elevation(child_xy[c][0], child_xy[c][1]));
      const std::size_t k = particles.add(child_mass, foot, particles.velocity(i), child_radius);
      particles.ax[k] = particles.ax[i];
      particles.ay[k] = particles.ay[i];
      particles.az[k] = particles.az[i];
      particles.density[k] = particles.density[i];
      particles.depth[k] = particles.depth[i];
      particles.pressure[k] = particles.pressure[i];
      particles.still_time[k] = particles.still_time[i];
      particles.level[k] = particles.level[i];
    }
    particles.mass[i] = child_mass;
    particles.radius[i] = child_radius;
    particles.x[i] = child_xy[0][0];
    particles.y[i] = child_xy[0][1];
    particles.z[i] = ground.elevation(child_xy[0][0], child_xy[0][1]);
    ++splits;
  }
  return splits;
}

}  // namespace talus
