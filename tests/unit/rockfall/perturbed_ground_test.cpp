// Tests of the perturbed ground of paper 3.4 (src/ground/perturbed_ground.cpp; kept with the
// rock-fall tests that use it): no noise gives the ground model back exactly; with noise, height
// z + A Perlin, a normal matching the height's slope, at() equal to the three separate calls,
// and the trajectory's material variation.
#include "talus/ground/perturbed_ground.hpp"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "../../validation/synthetic_ground.hpp"

namespace talus {
namespace {

// A 12 x 10 grid of 4 m cells with rough elevations and two lithologies (noise 0.3 m and 0).
GroundModel rough_model() {
  const GridSpec spec = testing_ground::local_spec(12, 10, 4.0);
  Grid<double> z(spec);
  Grid<GroundMaterial> materials(spec);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) {
      z.at(col, row) = 100.0 + 3.0 * std::sin(0.9 * col + 0.4 * row * row) - 2.0 * col;
      materials.at(col, row) = col < 6 ? testing_ground::fast_material(0.4, 0.7, 0.5, 0.01, 0.3)
                                       : testing_ground::fast_material(0.9, 0.95, 0.3, 0.0, 0.0);
    }
  }
  return GroundModel(std::move(z), std::move(materials));
}

PerlinNoise unit_noise() {
  PerlinParameters parameters;
  parameters.base_frequency = 0.8;
  parameters.amplitude = 1.0;
  parameters.octaves = 3;
  parameters.seed = 11;
  return PerlinNoise(parameters);
}

// 400 points spread over the grid by irrational steps, so that none sits on a lattice line.
std::vector<Eigen::Vector2d> points() {
  std::vector<Eigen::Vector2d> p;
  for (int i = 0; i < 400; ++i) {
    const double u = i * 0.6180339887 - std::floor(i * 0.6180339887);
    const double v = i * 0.4142135624 - std::floor(i * 0.4142135624);
    p.emplace_back(0.3 + 43.1 * u, -0.2 - 35.5 * v);
  }
  return p;
}

TEST(PerturbedGround, WithoutNoiseItIsTheGroundModel) {
  const GroundModel model = rough_model();
  const PerturbedGround ground(model, nullptr);
  for (const Eigen::Vector2d& p : points()) {
    EXPECT_EQ(ground.height(p.x(), p.y()), model.elevation(p.x(), p.y()));
    EXPECT_EQ(ground.normal(p.x(), p.y()), model.normal(p.x(), p.y()));
    const GroundMaterial a = ground.material(p.x(), p.y()), b = model.material(p.x(), p.y());
    EXPECT_EQ(a.friction, b.friction);
    EXPECT_EQ(a.restitution_normal, b.restitution_normal);
    EXPECT_EQ(a.vegetation_deperdition, b.vegetation_deperdition);
    EXPECT_EQ(ground.contains(p.x(), p.y()), model.contains(p.x(), p.y()));
  }
}

TEST(PerturbedGround, HeightIsElevationPlusAmplitudeTimesNoise) {
  const GroundModel model = rough_model();
  const PerlinNoise noise = unit_noise();
  const PerturbedGround ground(model, &noise);
  int noisy = 0;
  for (const Eigen::Vector2d& p : points()) {
    const double amplitude = model.material(p.x(), p.y()).noise_amplitude;
    const double expected = model.elevation(p.x(), p.y()) + amplitude * noise(p.x(), p.y());
    EXPECT_NEAR(ground.height(p.x(), p.y()), expected, 1e-12);
    if (amplitude == 0.0) {
      EXPECT_EQ(ground.height(p.x(), p.y()), model.elevation(p.x(), p.y()));
    }
    if (std::abs(ground.height(p.x(), p.y()) - model.elevation(p.x(), p.y())) > 1e-3) ++noisy;
  }
  EXPECT_GT(noisy, 100);
}

// Where the amplitude is constant (left lithology, away from its boundary), the normal is the
// height's slope: compare with central differences.
TEST(PerturbedGround, NormalFollowsTheHeightsSlope) {
  const GroundModel model = rough_model();
  const PerlinNoise noise = unit_noise();
  const PerturbedGround ground(model, &noise);
  const double h = 1e-6;
  for (const Eigen::Vector2d& p : points()) {
    if (p.x() > 18.0) continue;
    const double gx = (ground.height(p.x() + h, p.y()) - ground.height(p.x() - h, p.y())) / (2 * h);
    const double gy = (ground.height(p.x(), p.y() + h) - ground.height(p.x(), p.y() - h)) / (2 * h);
    const Eigen::Vector3d expected = Eigen::Vector3d(-gx, -gy, 1.0).normalized();
    EXPECT_LT((ground.normal(p.x(), p.y()) - expected).norm(), 1e-5) << p.transpose();
  }
}

TEST(PerturbedGround, AtEqualsTheSeparateCalls) {
  const GroundModel model = rough_model();
  const PerlinNoise noise = unit_noise();
  const PerturbedGround ground(model, &noise, MaterialVariation{1.2, 0.9, 1.1});
  for (const Eigen::Vector2d& p : points()) {
    const GroundPoint point = ground.at(p.x(), p.y());
    EXPECT_EQ(point.height, ground.height(p.x(), p.y()));
    EXPECT_EQ(point.normal, ground.normal(p.x(), p.y()));
    EXPECT_EQ(point.material.friction, ground.material(p.x(), p.y()).friction);
    EXPECT_EQ(point.material.restitution_normal, ground.material(p.x(), p.y()).restitution_normal);
  }
}

TEST(PerturbedGround, MaterialVariationScalesAndCapsRestitutions) {
  const GroundModel model = rough_model();
  const PerturbedGround ground(model, nullptr, MaterialVariation{1.3, 1.2, 0.8});
  const GroundMaterial left = ground.material(4.0, -8.0);   // Rn 0.4, Rt 0.7, mu 0.5
  EXPECT_NEAR(left.restitution_normal, 0.52, 1e-12);
  EXPECT_NEAR(left.restitution_tangential, 0.84, 1e-12);
  EXPECT_NEAR(left.friction, 0.4, 1e-12);
  const GroundMaterial right = ground.material(40.0, -8.0);  // Rn 0.9, Rt 0.95: capped
  EXPECT_EQ(right.restitution_normal, 1.0);
  EXPECT_EQ(right.restitution_tangential, 1.0);
  EXPECT_EQ(right.vegetation_deperdition, model.material(40.0, -8.0).vegetation_deperdition);
}

}  // namespace
}  // namespace talus
