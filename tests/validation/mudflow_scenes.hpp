// Ground models, releases and measures built in memory for the mud-flow validation tests
// (tests/validation/mudflow_*_test.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include "synthetic_ground.hpp"
#include "talus/core/release.hpp"
#include "talus/mudflow/mudflow_simulation.hpp"

namespace talus::mudflow_scenes {

// A north-up grid of width x height square cells of `cell` m whose lower-left corner is at
// (x0, y0 - height cell) and upper-left corner at (x0, y0).
inline GridSpec grid(int width, int height, double cell, double x0, double y0) {
  GridSpec spec = testing_ground::local_spec(width, height, cell);
  spec.geotransform = {x0, cell, 0.0, y0, 0.0, -cell};
  return spec;
}

// Ground of elevation z(x, y) without vegetation (the mud's basal friction is a rheology setting,
// not the ground's).
inline GroundModel ground(const GridSpec& spec, const std::function<double(double, double)>& z) {
  return testing_ground::make_ground(spec, z, testing_ground::fast_material(0.0, 0.0, 0.0));
}

// A release of depth(x, y) (m, vertical, per horizontal area) in every cell, at its centre.
inline ReleaseSet release(const GridSpec& spec, const std::function<double(double, double)>& depth) {
  ReleaseSet set;
  set.depth = Grid<float>(spec, 0.0f);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) {
      set.depth.at(col, row) = static_cast<float>(std::max(0.0, depth(spec.node_x(col), spec.node_y(row))));
    }
  }
  return set;
}

// The sum of a layer over its valid cells times the cell area (m3 for a depth layer).
inline double layer_volume(const Grid<float>& layer) {
  double sum = 0;
  for (std::size_t i = 0; i < layer.size(); ++i) {
    if (layer.is_valid(i)) sum += layer[i];
  }
  return sum * layer.spec().cell_area();
}

// The mass front of a snapshot: the farthest position s along +x (m, measured along a slope of
// angle phi) beyond which the particles with |y| < half_band hold `volume_per_width` (m3 per m of
// `width`, the width they fill). Returns -infinity when they hold less.
inline double mass_front(const ParticleSnapshot& shot, double phi, double half_band, double width,
                         double volume_per_width, double mud_density) {
  std::vector<std::pair<double, double>> along;  // (s, volume per width)
  for (std::size_t i = 0; i < shot.x.size(); ++i) {
    if (std::abs(shot.y[i]) < half_band) along.push_back({shot.x[i] / std::cos(phi), shot.mass[i] / mud_density / width});
  }
  std::sort(along.begin(), along.end());
  double beyond = 0;
  for (std::size_t k = along.size(); k-- > 0;) {
    beyond += along[k].second;
    if (beyond >= volume_per_width) return along[k].first;
  }
  return -std::numeric_limits<double>::infinity();
}

// The snapshot taken at `time` (s), or null when there is none.
inline const ParticleSnapshot* snapshot_at(const MudflowResult& result, double time) {
  for (const ParticleSnapshot& shot : result.snapshots) {
    if (std::abs(shot.time - time) < 1e-9) return &shot;
  }
  return nullptr;
}

// Total energy (J) of one history point: kinetic, potential and internal.
inline double total_energy(const MudflowHistoryPoint& point) {
  return point.kinetic_energy + point.potential_energy + point.internal_energy;
}

// A chute: a 30 degree slope down to x = 25 m, then a flat runout, 50 m wide, with Coulomb
// friction tan(20 deg); a 15 m x 12 m x 2 m release on the slope, and an optional bed of 0.5 m of
// erodible material on the slope's lower part (x in [2, 22] m, |y| < 10 m). The flow stops on the
// runout well inside the ground (no outflow).
struct Chute {
  GridSpec spec = grid(100, 50, 1.0, -20.0, 25.0);
  GroundModel ground_model =
      ground(spec, [](double x, double) { return std::tan(std::numbers::pi / 6.0) * std::max(0.0, 25.0 - x); });
  ReleaseSet release_set =
      release(spec, [](double x, double y) { return (x > -15.0 && x < 0.0 && std::abs(y) < 6.0) ? 2.0 : 0.0; });
  Grid<float> erodible = erodible_bed(spec);

  static Grid<float> erodible_bed(const GridSpec& spec) {
    Grid<float> bed(spec, 0.0f);
    for (int row = 0; row < spec.height; ++row) {
      for (int col = 0; col < spec.width; ++col) {
        const double x = spec.node_x(col), y = spec.node_y(row);
        if (x > 2.0 && x < 22.0 && std::abs(y) < 10.0) bed.at(col, row) = 0.5f;
      }
    }
    return bed;
  }
  static MudflowSettings settings(bool adaptive, int threads) {
    MudflowSettings s;
    s.duration = 40.0;
    s.particle_size = 0.5;
    s.adaptive = adaptive;
    s.threads = threads;
    s.rheology.rheology = Rheology::coulomb;
    s.rheology.friction = std::tan(std::numbers::pi / 9.0);
    s.entrainment_rate = 0.02;
    s.release_thickness = ReleaseThickness::vertical;  // the scene's depths are heights of vertical columns
    return s;
  }
};

}  // namespace talus::mudflow_scenes
