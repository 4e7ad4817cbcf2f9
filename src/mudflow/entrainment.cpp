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

// Per particle: the demanded depth d = E h |u| step (m) over its footprint, a square of area
// a = m / sigma (m2; the cell area when sigma is 0) centred on it. Each DEM cell k it overlaps by
// a_k (m2) gives dz_k = min(d, remaining_k) over a_k, so volume_k = dz_k a_k (m3) and the cell's
// depth falls by volume_k / A (A the cell area). The mass gain rho0 sum_k volume_k (kg) joins
// the particle with its momentum unchanged (velocity x m / (m + dm)).
double Entrainment::erode(ParticleSet& particles, const std::vector<char>& active, double step, Grid<float>& eroded) {
  require_same_grid(eroded.spec(), ground_.spec(), "eroded depth and DEM");
  const GridSpec& spec = ground_.spec();
  const double cell_area = spec.cell_area();
  const double cell_width = std::abs(spec.geotransform[1]), cell_height = std::abs(spec.geotransform[5]);
  double entrained = 0;  // m3
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (!active.empty() && !active[i]) continue;
    if (particles.state[i] != ParticleState::flowing) continue;
    const double demanded = rate_ * particles.depth[i] * particles.velocity(i).norm() * step;  // m
    if (!(demanded > 0.0)) continue;
    const double mass = particles.mass[i];
    const double sigma = particles.density[i];
    const double side = std::sqrt(sigma > 0.0 ? mass / sigma : cell_area);  // m
    // The footprint in continuous cell coordinates of the whole grid (cell (col, row) spans
    // [col, col + 1) x [row, row + 1)); on a tile's window (GridSpec) its cells are offset, so that
    // the fractions are those of the whole grid, bit for bit.
    const double u = (particles.x[i] - spec.geotransform[0]) / spec.geotransform[1];
    const double v = (particles.y[i] - spec.geotransform[3]) / spec.geotransform[5];
    const double half_u = 0.5 * side / cell_width, half_v = 0.5 * side / cell_height;
    if (!(std::isfinite(u) && std::isfinite(v) && std::isfinite(half_u) && std::isfinite(half_v))) continue;
    const int col_first = std::max(spec.col_offset, static_cast<int>(std::floor(u - half_u)));
    const int col_last = std::min(spec.col_offset + spec.width - 1, static_cast<int>(std::floor(u + half_u)));
    const int row_first = std::max(spec.row_offset, static_cast<int>(std::floor(v - half_v)));
    const int row_last = std::min(spec.row_offset + spec.height - 1, static_cast<int>(std::floor(v + half_v)));
    double volume = 0;  // m3 from every cell
    for (int row = row_first; row <= row_last; ++row) {
      // Fractions of a cell's width and height (-) that the footprint covers.
      const double overlap_v = std::min(row + 1.0, v + half_v) - std::max(static_cast<double>(row), v - half_v);
      if (!(overlap_v > 0.0)) continue;
      for (int col = col_first; col <= col_last; ++col) {
        const double overlap_u = std::min(col + 1.0, u + half_u) - std::max(static_cast<double>(col), u - half_u);
        const std::size_t cell = remaining_.index(col - spec.col_offset, row - spec.row_offset);
        double& left = remaining_[cell];
        if (!(left > 0.0) || !(overlap_u > 0.0)) continue;
        const double cell_depth = std::min(demanded, left) * overlap_u * overlap_v;  // m over the whole cell
        left = std::max(0.0, left - cell_depth);
        eroded[cell] += static_cast<float>(cell_depth);
        volume += cell_depth * cell_area;
      }
    }
    if (!(volume > 0.0)) continue;
    const double gained = mud_density_ * volume;
    const double scale = mass / (mass + gained);
    particles.vx[i] *= scale;
    particles.vy[i] *= scale;
    particles.vz[i] *= scale;
    particles.mass[i] = mass + gained;
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
