// The mud-flow layers (docs/architecture.md section 3) from the particles' volumes spread onto the DEM
// cells with the smoothing kernel (paper 4.1), serially in index order.
#include "talus/mudflow/flow_maps.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "talus/mudflow/flow_density.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"
#include "talus/mudflow/surface_following.hpp"

namespace talus {
namespace {

// The arrival time (s) written for cells the flow covers at release, the first instant.
constexpr double kReleaseArrival = 0.001;

// The share of the kernel's central weight below which a cell takes no part of a particle's
// volume in the maps (find_footprint).
constexpr double kTraceWeight = 1e-6;

// The integer node coordinates k with low <= k <= high (low <= high) inside [0, count - 1];
// false when there are none.
bool node_range(double low, double high, int count, int& first, int& last) {
  if (!(high >= 0.0) || !(low <= count - 1.0)) return false;
  first = static_cast<int>(std::ceil(std::max(low, 0.0)));
  last = static_cast<int>(std::floor(std::min(high, count - 1.0)));
  return first <= last;
}

}  // namespace

// Empty layers (0, nodata off the valid area) and cos(theta) per cell, computed once.
FlowMaps::FlowMaps(const GroundModel& ground, double mud_density, double arrival_depth, bool with_erosion,
                   double smallest_smoothing)
    : ground_(ground),
      mud_density_(mud_density),
      arrival_depth_(arrival_depth),
      min_spreading_radius_(kSpreadingRadiusPerCell * std::max(std::abs(ground.spec().geotransform[1]),
                                                              std::abs(ground.spec().geotransform[5]))),
      smallest_smoothing_(smallest_smoothing) {
  const Grid<double>& dem = ground.elevation_grid();
  const GridSpec& spec = dem.spec();
  Grid<float> empty(spec, 0.0f);
  cos_slope_.assign(spec.cell_count(), 1.0);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) {
      const std::size_t cell = dem.index(col, row);
      if (dem.is_valid(cell)) {
        cos_slope_[cell] = cell_cos_slope(ground, col, row);
      } else {
        empty[cell] = static_cast<float>(spec.nodata);
      }
    }
  }
  layers_.flow_depth_max = empty;
  layers_.velocity_max = empty;
  layers_.pressure_max = empty;
  layers_.deposit_depth = empty;
  layers_.arrival_time = empty;
  if (with_erosion) layers_.erosion_depth = empty;
  reached_.assign(spec.cell_count(), 0);
  spread_depth_.assign(spec.cell_count(), 0.0);
  spread_speed_depth_.assign(spec.cell_count(), 0.0);
}

// Cells whose centres lie within the spreading radius, weighted by the kernel W(|c - x|, radius)
// (smoothing_kernel.hpp) and normalised to sum 1 over the valid ones. The radius is at least 1.5
// cells, so the centre of the cell holding (x, y) (at most 0.71 cells away) is always among them:
// only a particle whose own cell is invalid can find no valid centre, and it leaves nothing.
// A centre in the kernel's last fringe, where W falls below kTraceWeight of its central value
// (the outer 2% of the radius for Wendland's kernel), takes no share: it would hold a trace of mud (down to 1e-16 m)
// that no map can show, a cell "reached" that draws as never reached.
void FlowMaps::find_footprint(double x, double y, double radius) {
  footprint_.clear();
  const Grid<double>& dem = ground_.elevation_grid();
  const GridSpec& spec = dem.spec();
  const double col_a = spec.col_of(x - radius), col_b = spec.col_of(x + radius);
  const double row_a = spec.row_of(y - radius), row_b = spec.row_of(y + radius);
  int col0 = 0, col1 = -1, row0 = 0, row1 = -1;
  if (!node_range(std::min(col_a, col_b), std::max(col_a, col_b), spec.width, col0, col1)) return;
  if (!node_range(std::min(row_a, row_b), std::max(row_a, row_b), spec.height, row0, row1)) return;
  const double radius_squared = radius * radius;
  const double least_weight = kTraceWeight * kernel_value(0.0, radius);
  double total = 0;  // sum of the kernel weights (1/m2)
  for (int row = row0; row <= row1; ++row) {
    const double dy = spec.node_y(row) - y;
    for (int col = col0; col <= col1; ++col) {
      const std::size_t cell = dem.index(col, row);
      if (!dem.is_valid(cell)) continue;
      const double dx = spec.node_x(col) - x;
      const double r_squared = dx * dx + dy * dy;
      if (r_squared >= radius_squared) continue;
      const double weight = kernel_value(std::sqrt(r_squared), radius);
      if (weight <= least_weight) continue;
      footprint_.push_back({cell, weight});
      total += weight;
    }
  }
  for (CellShare& share : footprint_) share.weight /= total;
}

// Normal depth of cell c from particle i: V w_c / A x cos(theta_c), V = m / rho0 (m3), A the
// cell area (m2): the horizontal column V w_c / A measured normal to the ground. The weights w_c
// spread over i's smoothing radius R_s (flow_density.hpp), the radius its own depth is summed
// with, so the maps show the depth the dynamics see.
void FlowMaps::spread(const ParticleSet& particles, std::size_t i, bool with_speed) {
  const double volume = particles.mass[i] / mud_density_;
  const double depth_per_weight = volume / ground_.spec().cell_area();  // m
  const double speed = with_speed ? particles.velocity(i).norm() : 0.0;  // m/s
  find_footprint(particles.x[i], particles.y[i],
                 std::max(smoothing_radius(particles, i, smallest_smoothing_), min_spreading_radius_));
  for (const CellShare& share : footprint_) {
    const double depth = depth_per_weight * share.weight * cos_slope_[share.cell];
    if (!(depth > 0.0)) continue;
    if (spread_depth_[share.cell] == 0.0) touched_.push_back(share.cell);
    spread_depth_[share.cell] += depth;
    spread_speed_depth_[share.cell] += depth * speed;
  }
}

// Zeroes the scratch cells of the previous sample or deposit (only those touched).
void FlowMaps::clear_spread() {
  for (const std::size_t cell : touched_) {
    spread_depth_[cell] = 0.0;
    spread_speed_depth_[cell] = 0.0;
  }
  touched_.clear();
}

// Maxima of depth (m), depth-weighted speed u (m/s) and impact pressure rho0 u^2 (kPa), and the
// first time (s) the depth exceeds the arrival depth; a cell covered at release takes
// kReleaseArrival, as 0 means "never reached" in every layer (docs/layers.md).
void FlowMaps::sample(const ParticleSet& particles, double time) {
  clear_spread();
  for (std::size_t i = 0; i < particles.size(); ++i) {
    if (particles.state[i] == ParticleState::flowing) spread(particles, i, true);
  }
  for (const std::size_t cell : touched_) {
    const double depth = spread_depth_[cell];
    const double speed = spread_speed_depth_[cell] / depth;
    const double pressure = mud_density_ * speed * speed / 1000.0;  // kPa
    float& depth_max = layers_.flow_depth_max[cell];
    float& speed_max = layers_.velocity_max[cell];
    float& pressure_max = layers_.pressure_max[cell];
    depth_max = std::max(depth_max, static_cast<float>(depth));
    speed_max = std::max(speed_max, static_cast<float>(speed));
    pressure_max = std::max(pressure_max, static_cast<float>(pressure));
    if (!reached_[cell] && depth > arrival_depth_) {
      reached_[cell] = 1;
      layers_.arrival_time[cell] = static_cast<float>(std::max(time, kReleaseArrival));
    }
  }
}

// Eroded depth (m) accumulated per cell (paper 4.1, entrainment).
void FlowMaps::add_erosion(std::size_t cell, double eroded_depth) {
  if (!layers_.erosion_depth) throw std::logic_error("flow maps: erosion added without an erosion layer");
  (*layers_.erosion_depth)[cell] += static_cast<float>(eroded_depth);
}

// Every particle's volume spread as normal depth (m); the volume (m3) is sum depth x A / cos.
double FlowMaps::deposit(const ParticleSet& particles) {
  clear_spread();
  for (std::size_t i = 0; i < particles.size(); ++i) spread(particles, i, false);
  const Grid<double>& dem = ground_.elevation_grid();
  Grid<float>& deposit_depth = layers_.deposit_depth;
  for (std::size_t cell = 0; cell < deposit_depth.size(); ++cell) {
    if (dem.is_valid(cell)) deposit_depth[cell] = 0.0f;
  }
  const double cell_area = ground_.spec().cell_area();
  double volume = 0;
  for (const std::size_t cell : touched_) {
    deposit_depth[cell] = static_cast<float>(spread_depth_[cell]);
    volume += spread_depth_[cell] * cell_area / cos_slope_[cell];
  }
  return volume;
}

}  // namespace talus
