// Release of the mud as particles (issue 5, docs/architecture.md section 3 --release; paper 4.1).
#include "talus/mudflow/release_particles.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <vector>

#include "talus/core/counter_random.hpp"
#include "talus/core/errors.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"
#include "talus/mudflow/surface_following.hpp"

namespace talus {
namespace {

// The lattice of one cell-sized column: places per axis and their steps (m).
struct CellLattice {
  int columns = 1, rows = 1;
  double step_x = 0, step_y = 0;  // m
  double support_radius = 0;      // m
};

// n = max(1, round(cell side / spacing)) places per axis; kernel support from the lattice step.
CellLattice lattice_for(const GridSpec& spec, double spacing) {
  CellLattice lattice;
  lattice.columns = std::max(1, static_cast<int>(std::lround(spec.cell_width() / spacing)));
  lattice.rows = std::max(1, static_cast<int>(std::lround(spec.cell_height() / spacing)));
  lattice.step_x = spec.cell_width() / lattice.columns;
  lattice.step_y = spec.cell_height() / lattice.rows;
  lattice.support_radius = kSupportPerSpacing * std::sqrt(lattice.step_x * lattice.step_y);
  return lattice;
}

// Adds the particles of one cell-sized column of `column_mass` (kg) centred on (cx, cy) (m),
// shared by the lattice places on the ground surface, at rest on it.
void release_column(const GroundModel& ground, const ReleaseLayout& layout, const CellLattice& lattice, double cx,
                    double cy, double column_mass, std::uint64_t source, ParticleSet& particles) {
  const double width = lattice.step_x * lattice.columns, height = lattice.step_y * lattice.rows;  // m
  std::vector<Eigen::Vector2d> places;
  places.reserve(static_cast<std::size_t>(lattice.columns) * static_cast<std::size_t>(lattice.rows));
  for (int row = 0; row < lattice.rows; ++row) {
    for (int col = 0; col < lattice.columns; ++col) {
      const std::uint64_t place = static_cast<std::uint64_t>(row) * static_cast<std::uint64_t>(lattice.columns) +
                                  static_cast<std::uint64_t>(col);
      CounterRandom random(layout.seed, source, place);
      const Eigen::Vector2d lattice_point(cx - 0.5 * width + (col + 0.5) * lattice.step_x,
                                          cy + 0.5 * height - (row + 0.5) * lattice.step_y);
      const double shift_x = random.uniform(-0.5, 0.5) * layout.jitter * lattice.step_x;
      const double shift_y = random.uniform(-0.5, 0.5) * layout.jitter * lattice.step_y;
      const Eigen::Vector2d jittered = lattice_point + Eigen::Vector2d(shift_x, shift_y);
      if (ground.contains(jittered.x(), jittered.y())) {
        places.push_back(jittered);
      } else if (ground.contains(lattice_point.x(), lattice_point.y())) {
        places.push_back(lattice_point);
      }
    }
  }
  if (places.empty()) return;
  const double particle_mass = column_mass / static_cast<double>(places.size());
  for (const Eigen::Vector2d& p : places) {
    particles.add(particle_mass, {p.x(), p.y(), ground.elevation(p.x(), p.y())}, Eigen::Vector3d::Zero(),
                  lattice.support_radius);
  }
}

// The most particles a release may create: each costs about 1 kB with its neighbour list, and a
// flow of more would take days on the machines Talus is meant for. A particle size given in
// millimetres instead of metres is refused with a message instead of exhausting the memory.
constexpr double kMostReleasedParticles = 4e6;

// Refuses a release that would create more than kMostReleasedParticles (InputError, exit code 2).
void check_particle_count(const GridSpec& spec, const ReleaseSet& release, const ReleaseLayout& layout) {
  double columns = 0;
  for (std::size_t cell = 0; cell < release.depth.size(); ++cell) columns += release.depth[cell] > 0.0f ? 1.0 : 0.0;
  for (const ReleasePoint& point : release.points) columns += point.depth > 0.0 ? 1.0 : 0.0;
  const double places = std::max(1.0, std::round(spec.cell_width() / layout.spacing)) *
                        std::max(1.0, std::round(spec.cell_height() / layout.spacing));
  if (columns * places > kMostReleasedParticles) {
    std::ostringstream message;
    const double count = columns * places;
    message.precision(3);  // in digits up to 10^15, beyond that as 1e+20: no rounding that overflows
    message << "mud flow: the release would create ";
    if (count < 1e15) {
      message << std::llround(count);
    } else {
      message << count;
    }
    message << " particles (more than " << std::llround(kMostReleasedParticles) << ") " << layout.spacing
            << " m apart: use a larger particle size";
    throw InputError(message.str());
  }
}

// Refuses layouts no release can be built from (InputError, exit code 2).
void check_layout(const ReleaseLayout& layout) {
  if (!(layout.spacing > 0.0 && std::isfinite(layout.spacing))) {
    throw InputError("mud flow: particle spacing must be > 0 m");
  }
  if (!(layout.mud_density > 0.0 && std::isfinite(layout.mud_density))) {
    throw InputError("mud flow: mud density must be > 0 kg/m3");
  }
  if (!(layout.jitter >= 0.0 && layout.jitter <= 1.0)) throw InputError("mud flow: release jitter must be in [0, 1]");
}

// d A (m3) of a cell-sized column of depth d (m) at DEM cell (col, row), divided by cos(theta) there
// when d is the thickness normal to the ground (docs/inputs.md, "How a mud-flow depth is measured").
double column_volume(const GroundModel& ground, ReleaseThickness thickness, int col, int row, double depth) {
  const double vertical = depth * ground.spec().cell_area();
  if (thickness == ReleaseThickness::vertical) return vertical;
  return vertical / cell_cos_slope(ground, col, row);
}

// Calls column(x, y, col, row, depth, source) for each released column: the cells with depth > 0
// on valid DEM nodes in index order (source: the cell's index on the whole grid, so that a
// window's particles are the whole run's, issue 19), then the points with depth > 0 on a valid
// cell, each centred on itself over the cell under it (source: whole cell count + point index).
template <typename Column>
void for_each_released_column(const GroundModel& ground, const ReleaseSet& release, Column column) {
  const GridSpec& spec = ground.spec();
  const Grid<double>& dem = ground.elevation_grid();
  if (release.depth.size() > 0) {
    require_same_grid(release.depth.spec(), spec, "mud-flow release depth and DEM");
    for (int row = 0; row < spec.height; ++row) {
      for (int col = 0; col < spec.width; ++col) {
        const std::size_t cell = dem.index(col, row);
        const double depth = static_cast<double>(release.depth[cell]);
        if (!(depth > 0.0) || !dem.is_valid(cell)) continue;
        column(spec.node_x(col), spec.node_y(row), col, row, depth, spec.whole_index(cell));
      }
    }
  }
  for (std::size_t k = 0; k < release.points.size(); ++k) {
    const ReleasePoint& point = release.points[k];
    if (!(point.depth > 0.0)) continue;
    const double col_at = spec.col_of(point.x), row_at = spec.row_of(point.y);  // cells, from the first centre
    if (!(col_at > -0.5 && col_at < spec.width - 0.5 && row_at > -0.5 && row_at < spec.height - 0.5)) continue;
    const int col = static_cast<int>(std::lround(col_at)), row = static_cast<int>(std::lround(row_at));
    if (!dem.is_valid(col, row)) continue;
    column(point.x, point.y, col, row, point.depth, spec.whole().cell_count() + k);
  }
}

}  // namespace

ReleaseThicknessChoice parse_release_thickness(const std::string& text) {
  if (text == "auto") return ReleaseThicknessChoice::automatic;
  if (text == "normal") return ReleaseThicknessChoice::normal;
  if (text == "vertical") return ReleaseThicknessChoice::vertical;
  throw InputError("unknown release thickness '" + text + "': expected auto, normal or vertical");
}

const char* to_string(ReleaseThickness thickness) {
  return thickness == ReleaseThickness::normal ? "normal" : "vertical";
}

const char* to_string(ReleaseThicknessChoice choice) {
  return choice == ReleaseThicknessChoice::automatic ? "auto" : choice == ReleaseThicknessChoice::normal ? "normal" : "vertical";
}

// Cells in index order, then points (docs/architecture.md section 3 --release), each a column of rho0 d A.
ParticleSet release_particles(const GroundModel& ground, const ReleaseSet& release, const ReleaseLayout& layout) {
  check_layout(layout);
  check_particle_count(ground.spec(), release, layout);
  const CellLattice lattice = lattice_for(ground.spec(), layout.spacing);
  ParticleSet particles;
  for_each_released_column(ground, release, [&](double x, double y, int col, int row, double depth, std::uint64_t source) {
    const double mass = layout.mud_density * column_volume(ground, layout.thickness, col, row, depth);
    release_column(ground, layout, lattice, x, y, mass, source, particles);
  });
  return particles;
}

double release_volume(const GroundModel& ground, const ReleaseSet& release, ReleaseThickness thickness) {
  double volume = 0;
  for_each_released_column(ground, release, [&](double, double, int col, int row, double depth, std::uint64_t) {
    volume += column_volume(ground, thickness, col, row, depth);
  });
  return volume;
}

ReleaseThickness thickness_for_release(ReleaseThicknessChoice choice, const ReleaseSet& release) {
  if (choice == ReleaseThicknessChoice::normal) return ReleaseThickness::normal;
  if (choice == ReleaseThicknessChoice::vertical) return ReleaseThickness::vertical;
  return release.depths_from_surface_lowering ? ReleaseThickness::vertical : ReleaseThickness::normal;
}

}  // namespace talus
