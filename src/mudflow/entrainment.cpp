// Entrainment of the erodible bed by the flowing particles (paper 4.1; McDougall & Hungr 2005),
// serially in index order.
#include "talus/mudflow/entrainment.hpp"

#include <algorithm>
#include <cmath>

namespace talus {

// The erodible depth (m) per valid cell; everything else holds none.
Entrainment::Entrainment(const GroundModel& ground, const Grid<float>& erodible, double rate, double mud_density)
    : ground_(ground), remaining_(ground.spec(), 0.0), rate_(rate), mud_density_(mud_density) {
  require_same_grid(erodible.spec(), ground.spec(), "erodible depth and DEM");
  const Grid<double>& dem = ground.elevation_grid();
  for (std::size_t cell = 0; cell < remaining_.size(); ++cell) {
    if (erodible.is_valid(cell) && dem.is_valid(cell) && erodible[cell] > 0.0f) {
      remaining_[cell] = static_cast<double>(erodible[cell]);
    }
  }
}

// Per particle: eroded depth dz = min(E h |u| step, remaining) (m) under its footprint a =
// min(m / sigma, A) (m2), mass gain dm = rho0 dz a (kg), velocity x m / (m + dm) (momentum
// unchanged), cell depth reduced by dz a / A (m).
double Entrainment::erode(ParticleSet& particles, const std::vector<char>& active, double step, Grid<float>& eroded) {
  require_same_grid(eroded.spec(), ground_.spec(), "eroded depth and DEM");
  const GridSpec& spec = ground_.spec();
  const double cell_area = spec.cell_area();
  double entrained = 0;  // m3
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!active.empty() && !active[i]) continue;
    if (particles.state[i] != ParticleState::flowing) continue;
    const double col = std::floor((particles.x[i] - spec.geotransform[0]) / spec.geotransform[1]);
    const double row = std::floor((particles.y[i] - spec.geotransform[3]) / spec.geotransform[5]);
    if (!(col >= 0.0 && col < spec.width && row >= 0.0 && row < spec.height)) continue;
    const std::size_t cell = remaining_.index(static_cast<int>(col), static_cast<int>(row));
    double& left = remaining_[cell];
    if (!(left > 0.0)) continue;
    const double speed = particles.velocity(i).norm();
    const double eroded_depth = std::min(rate_ * particles.depth[i] * speed * step, left);
    if (!(eroded_depth > 0.0)) continue;
    const double mass = particles.mass[i];
    const double sigma = particles.density[i];
    const double footprint = sigma > 0.0 ? std::min(mass / sigma, cell_area) : cell_area;
    const double volume = eroded_depth * footprint;
    const double gained = mud_density_ * volume;
    const double scale = mass / (mass + gained);
    particles.vx[i] *= scale;
    particles.vy[i] *= scale;
    particles.vz[i] *= scale;
    particles.mass[i] = mass + gained;
    const double cell_depth = volume / cell_area;
    left = std::max(0.0, left - cell_depth);
    eroded[cell] += static_cast<float>(cell_depth);
    entrained += volume;
  }
  return entrained;
}

// Sum of the remaining depths (m) x cell area (m2).
double Entrainment::remaining_volume() const {
  double depth_sum = 0;
  for (std::size_t cell = 0; cell < remaining_.size(); ++cell) depth_sum += remaining_[cell];
  return depth_sum * ground_.spec().cell_area();
}

}  // namespace talus
