// Ground models and a recording observer built in memory for the rock-fall tests (planes,
// steps, ridges on local north-up grids), shared by tests/validation and tests/unit/rockfall.
#pragma once

#include <functional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "talus/core/grid.hpp"
#include "talus/ground/ground_model.hpp"
#include "talus/rockfall/trajectory_observer.hpp"

namespace talus::testing_ground {

// A local north-up grid of width x height square cells of `cell` metres whose first node
// (col 0, row 0) sits at x = 0, y = 0; rows run towards -y.
inline GridSpec local_spec(int width, int height, double cell) {
  GridSpec spec;
  spec.width = width;
  spec.height = height;
  spec.geotransform = {-0.5 * cell, cell, 0.0, 0.5 * cell, 0.0, -cell};
  return spec;
}

// Fast-mode material: normal and tangential restitution, friction (sliding and rolling alike),
// vegetation, noise amplitude.
inline GroundMaterial fast_material(double restitution_normal, double restitution_tangential, double friction,
                                    double deperdition = 0.0, double noise_amplitude = 0.0) {
  GroundMaterial material;
  material.restitution_normal = restitution_normal;
  material.restitution_tangential = restitution_tangential;
  material.friction = friction;
  material.rolling_friction = friction;
  material.vegetation_deperdition = deperdition;
  material.noise_amplitude = noise_amplitude;
  return material;
}

// Elevation at each node from its (x, y), one material everywhere.
inline GroundModel make_ground(const GridSpec& spec, const std::function<double(double, double)>& elevation,
                               const GroundMaterial& material) {
  Grid<double> z(spec);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) z.at(col, row) = elevation(spec.node_x(col), spec.node_y(row));
  }
  return GroundModel(std::move(z), Grid<GroundMaterial>(spec, material));
}

// Everything a trajectory reports.
struct RecordedLoss {
  double x, y, friction, deformation;
};
class Recorder final : public TrajectoryObserver {
 public:
  void on_sample(const TrajectorySample& sample) override { samples.push_back(sample); }
  void on_energy_loss(double x, double y, double friction, double deformation) override {
    losses.push_back({x, y, friction, deformation});
  }
  void on_stop(const TrajectorySample& last, StopReason reason) override {
    final_sample = last;
    stop = reason;
    ++stops;
  }
  void on_restart(double) override { ++restarts; }
  double friction_loss() const {
    double sum = 0.0;
    for (const RecordedLoss& loss : losses) sum += loss.friction;
    return sum;
  }
  double deformation_loss() const {
    double sum = 0.0;
    for (const RecordedLoss& loss : losses) sum += loss.deformation;
    return sum;
  }

  std::vector<TrajectorySample> samples;
  std::vector<RecordedLoss> losses;
  TrajectorySample final_sample;
  StopReason stop = StopReason::max_time;
  int restarts = 0;  // the full model's restarts after failed steps
  int stops = 0;
};

}  // namespace talus::testing_ground
