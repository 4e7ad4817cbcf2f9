// Pressure, internal viscous friction and gravity on the mud columns (paper 4.1; docs/mudflow.md
// "Forces").
#include "talus/mudflow/flow_forces.hpp"

#include <algorithm>

#include "talus/core/errors.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"
#include "talus/mudflow/time_levels.hpp"

namespace talus {
namespace {

// eps^2 of the viscous term, per squared particle spacing (the pair's mean, so the pair term stays
// symmetric): keeps it finite when two feet meet (Morris et al. 1997 use 0.01 h^2).
constexpr double kViscousSofteningPerSpacing2 = 0.01;

}  // namespace

PressureColumn parse_pressure_column(const std::string& text) {
  if (text == "normal") return PressureColumn::normal;
  if (text == "vertical") return PressureColumn::vertical;
  throw InputError("unknown pressure column '" + text + "': expected normal or vertical");
}

const char* to_string(PressureColumn column) { return column == PressureColumn::normal ? "normal" : "vertical"; }

double pressure_slope_factor(PressureColumn column, double cos_slope) {
  return column == PressureColumn::normal ? cos_slope * cos_slope : 1.0;
}

// Pi_i / sigma_i^2 = g cos^2(theta_i) / (2 rho0) (m3/kg s2; g / (2 rho0) for the vertical
// column): with Pi proportional to sigma^2 the pressure term needs only the neighbours'
// positions and slopes, never their densities, so it is exact for particles whose neighbours are
// between their own steps.
FlowAcceleration flow_acceleration(const ParticleSet& particles, std::size_t i, const NeighbourList& neighbours,
                                   const FootNormals& normals, const FlowForceConstants& constants) {
  const double xi = particles.x[i], yi = particles.y[i];
  const double vxi = particles.vx[i], vyi = particles.vy[i], vzi = particles.vz[i];
  const double sigma_i = particles.density[i];
  const double factor_i = pressure_slope_factor(constants.pressure, normals.z[i]);
  const double pressure_scale = constants.gravity / (2.0 * constants.mud_density);
  const double radius_i = particles.radius[i];
  const double softening_scale = kViscousSofteningPerSpacing2 / (4.0 * kSupportPerSpacing * kSupportPerSpacing);
  const double nu = constants.internal_viscosity;
  const double* x = particles.x.data();
  const double* y = particles.y.data();
  const double* vx = particles.vx.data();
  const double* vy = particles.vy.data();
  const double* vz = particles.vz.data();
  const double* mass = particles.mass.data();
  const double* sigma = particles.density.data();
  const double* radius = particles.radius.data();
  const double* cos_slope = normals.z.data();

  double px = 0, py = 0;            // pressure (m/s2, horizontal)
  double fx = 0, fy = 0, fz = 0;    // viscosity (m/s2)
  double closing = 0;               // m/s
  double weights = 0, mvx = 0, mvy = 0, mvz = 0;  // the neighbours' share of sigma_i and of its momentum
  for (const NeighbourPair& pair : neighbours) {
    const std::size_t j = pair.index;
    if (constants.mean_velocity) {
      const double w = pair.weight;
      weights += w;
      mvx += w * vx[j];
      mvy += w * vy[j];
      mvz += w * vz[j];
    }
    const double dx = xi - x[j], dy = yi - y[j];
    const double dvx = vxi - vx[j], dvy = vyi - vy[j];
    closing = std::max(closing, approach_speed(dx, dy, dvx, dvy));
    const double factor_j = pressure_slope_factor(constants.pressure, cos_slope[j]);
    const double push = mass[j] * pressure_scale * (factor_i + factor_j) * pair.gradient_factor;
    px -= push * dx;
    py -= push * dy;
    if (nu > 0.0) {
      const double r2 = dx * dx + dy * dy;
      const double sigma_j = sigma[j];
      const double mean_radius = radius_i + radius[j];  // twice the pair's mean support radius (m)
      const double softening = softening_scale * mean_radius * mean_radius;
      const double drag = mass[j] * nu * (sigma_i + sigma_j) / (sigma_i * sigma_j) * pair.gradient_factor * r2 /
                          (r2 + softening);
      fx += drag * dvx;
      fy += drag * dvy;
      fz += drag * (vzi - vz[j]);
    }
  }
  const Eigen::Vector3d total(px + fx, py + fy, fz - constants.gravity);
  FlowAcceleration result{tangent_part(total, normals.at(i)), closing};
  if (constants.mean_velocity) {
    // The neighbours' mean, i itself left out: its own term m_i W(0) is about 40% of sigma_i at
    // 18 neighbours, and with it the departure would read 0.6 of the difference to the mud around.
    result.mean_velocity = weights > 0.0 ? Eigen::Vector3d(Eigen::Vector3d(mvx, mvy, mvz) / weights)
                                         : Eigen::Vector3d(vxi, vyi, vzi);
  }
  return result;
}

}  // namespace talus
