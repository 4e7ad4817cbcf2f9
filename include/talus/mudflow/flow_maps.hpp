// The mud-flow layers (docs/architecture.md section 3) gathered from the particles: each particle's volume
// is spread over the DEM cells whose centres lie within its spreading radius, max(R_s, 1.5 x
// the larger cell side) with R_s the smoothing radius its own depth is summed with
// (flow_density.hpp: R inside the flow, up to 4 R where it thins), with kernel weights
// W(r, spreading radius) normalised to one, so the depth maps hold exactly the particles'
// volume and a thinning margin is drawn as thin as the dynamics see it (issue 20). The floor of
// 1.5 cells keeps the maps smooth where particles are about as small as the cells or smaller: a
// uniform sheet of 2.5 m particles (R = 6 m) on 10 m cells gives interior depths within 0.002%
// (23% when spreading within R alone), of 5 m particles (R = 12 m) within 0.4% (3%). Per
// cell: the maxima over time of flow depth, velocity and impact pressure, the first time the
// flow was there, the depth left at the end and the depth eroded.
#pragma once

#include <cstddef>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "talus/core/grid.hpp"
#include "talus/ground/ground_model.hpp"
#include "talus/mudflow/particle_set.hpp"

namespace talus {

// The least spreading radius of a particle onto the cells, in larger cell sides (-).
inline constexpr double kSpreadingRadiusPerCell = 1.5;

struct FlowLayers {
  Grid<float> flow_depth_max;        // m, normal to the ground
  Grid<float> velocity_max;          // m/s
  Grid<float> pressure_max;          // kPa: impact pressure rho0 u^2
  Grid<float> deposit_depth;         // m, normal to the ground
  Grid<float> arrival_time;          // s; 0 where never reached, 0.001 where covered at release
  std::optional<Grid<float>> erosion_depth;  // m, only with an erodible raster
};

class FlowMaps {
 public:
  // Grids on the ground model's DEM grid; nodata outside its valid area (invalid DEM nodes), 0
  // elsewhere. mud_density rho0 (kg/m3); arrival_depth (m): a cell is reached when its flow
  // depth first exceeds it. smallest_smoothing (m): the least smoothing radius of the run's
  // particles (flow_density.hpp), so the layers spread each particle as the dynamics sum it.
  FlowMaps(const GroundModel& ground, double mud_density, double arrival_depth, bool with_erosion,
           double smallest_smoothing = std::numeric_limits<double>::infinity());

  // Samples the flow at `time` (s): depth and depth-weighted speed per cell from the flowing
  // particles, then the maxima and arrival times.
  void sample(const ParticleSet& particles, double time);
  // Adds eroded depth (m) in one cell (entrainment).
  void add_erosion(std::size_t cell, double eroded_depth);
  // The depth (m) every particle (flowing or deposited) leaves at the end, replacing any earlier
  // deposit; returns its volume (m3): the particles' volume up to rounding, less that of
  // particles outside the DEM's valid area.
  double deposit(const ParticleSet& particles);

  const FlowLayers& layers() const { return layers_; }
  FlowLayers take_layers() { return std::move(layers_); }

 private:
  struct CellShare {
    std::size_t cell;
    double weight;  // - ; the shares of one particle sum to 1
  };
  // The valid cells whose centres lie within `radius` (m) of (x, y) and their normalised kernel
  // weights, into footprint_.
  void find_footprint(double x, double y, double radius);
  // Spreads the volume of particle i (m3) as normal depth (m) into spread_depth_, and its
  // speed x depth into spread_speed_depth_ when asked; remembers the touched cells.
  void spread(const ParticleSet& particles, std::size_t i, bool with_speed);
  void clear_spread();

  const GroundModel& ground_;
  double mud_density_, arrival_depth_;
  double min_spreading_radius_;             // m: kSpreadingRadiusPerCell x the larger cell side
  double smallest_smoothing_;               // m: the particles' least smoothing radius
  FlowLayers layers_;
  std::vector<double> cos_slope_;           // - : cos(theta) of the ground at each cell centre
  std::vector<char> reached_;               // 1 once a cell's depth exceeded arrival_depth
  std::vector<double> spread_depth_;        // m: scratch of one sample or deposit
  std::vector<double> spread_speed_depth_;  // m2/s: scratch, sum of depth x speed
  std::vector<std::size_t> touched_;        // cells with a non-zero scratch value
  std::vector<CellShare> footprint_;        // scratch of find_footprint
};

}  // namespace talus
