// Tests of pressure, internal viscous friction and gravity on the columns (paper 4.1;
// docs/mudflow.md "Forces").
#include "talus/mudflow/flow_forces.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "talus/core/errors.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {
namespace {

constexpr double kRho = 2000.0;  // kg/m3
constexpr double kG = 9.81;      // m/s2

// Densities, neighbour lists and upward normals (flat ground) of every particle.
struct Evaluated {
  std::vector<NeighbourList> lists;
  FootNormals normals;
};
Evaluated evaluate(ParticleSet& p) {
  const std::size_t n = p.size();
  Evaluated e{std::vector<NeighbourList>(n), {}};
  e.normals.resize(n);
  std::vector<double> smoothing(n);
  for (std::size_t i = 0; i < n; ++i) smoothing[i] = smoothing_radius(p, i);
  PairSearch search;
  search.rebuild(p, smoothing, *std::min_element(p.radius.begin(), p.radius.end()));
  std::vector<double> sigma(n);
  for (std::size_t i = 0; i < n; ++i) sigma[i] = gather_density(p, search, i, smoothing[i], e.lists[i]);
  for (std::size_t i = 0; i < n; ++i) set_column_state(p, i, sigma[i], 1.0, {kRho, kG});
  return e;
}

TEST(FlowForces, PressureOnADepthRampIsMinusGTimesTheSlopeOfTheSurface) {
  // Columns 0.5 m apart whose depth grows as h = 1 + 0.05 x (m) on flat ground: the shallow-water
  // pressure acceleration is -g dh/dx = -0.4905 m/s2 along x.
  const double spacing = 0.5, slope = 0.05;
  ParticleSet p;
  for (int a = 0; a < 40; ++a) {
    for (int b = 0; b < 20; ++b) {
      const double x = a * spacing;
      p.add(kRho * (1.0 + slope * x) * spacing * spacing, {x, b * spacing, 0.0}, {0, 0, 0}, kSupportPerSpacing * spacing);
    }
  }
  Evaluated e = evaluate(p);
  const FlowForceConstants constants{kRho, kG, 0.0};
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int a = static_cast<int>(i / 20), b = static_cast<int>(i % 20);
    if (std::min({a, b, 39 - a, 19 - b}) < 4) continue;
    const Eigen::Vector3d acceleration = flow_acceleration(p, i, e.lists[i], e.normals, constants).acceleration;
    // 5%: the symmetric SPH gradient of a linear field over a square lattice at R = 2.4
    // spacings is 0.964 of the exact one (the lattice sum of x_j dW/dx s^2; 0.997 at R = 3).
    EXPECT_NEAR(acceleration.x(), -kG * slope, 0.05 * kG * slope) << i;
    EXPECT_NEAR(acceleration.y(), 0.0, 1e-3 * kG * slope) << i;
    EXPECT_EQ(acceleration.z(), 0.0);
  }
}

TEST(FlowForces, PressureAndViscosityConserveMomentum) {
  // A random cloud with random velocities and masses on flat ground, where gravity has no
  // tangential part: the internal forces sum to zero (1e-12 of the largest term).
  std::mt19937 generator(9);
  std::uniform_real_distribution<double> coordinate(0.0, 10.0), speed(-3.0, 3.0), mass(100.0, 400.0);
  ParticleSet p;
  for (int k = 0; k < 300; ++k) {
    p.add(mass(generator), {coordinate(generator), coordinate(generator), 0.0},
          {speed(generator), speed(generator), 0.0}, 1.2);
    p.density[k] = mass(generator);  // spread smoothing radii
  }
  Evaluated e = evaluate(p);
  const FlowForceConstants constants{kRho, kG, 0.7};
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  double scale = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Eigen::Vector3d force = p.mass[i] * flow_acceleration(p, i, e.lists[i], e.normals, constants).acceleration;
    total += force;
    scale = std::max(scale, force.norm());
  }
  EXPECT_LT(total.norm(), 1e-12 * scale * static_cast<double>(p.size()));
  EXPECT_GT(scale, 0.0);
}

TEST(FlowForces, ViscosityDrawsVelocitiesTogether) {
  // Two columns side by side moving in opposite directions: each is slowed towards the other.
  ParticleSet p;
  p.add(500.0, {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, 1.0);
  p.add(500.0, {0.4, 0.0, 0.0}, {0.0, 2.0, 0.0}, 1.0);
  Evaluated e = evaluate(p);
  const FlowForceConstants viscous{kRho, kG, 0.5}, inviscid{kRho, kG, 0.0};
  for (std::size_t i = 0; i < 2; ++i) {
    const Eigen::Vector3d friction = flow_acceleration(p, i, e.lists[i], e.normals, viscous).acceleration -
                                     flow_acceleration(p, i, e.lists[i], e.normals, inviscid).acceleration;
    const Eigen::Vector3d relative = p.velocity(i) - p.velocity(1 - i);
    EXPECT_LT(friction.dot(relative), 0.0) << i;
    EXPECT_NEAR(friction.normalized().dot(-relative.normalized()), 1.0, 1e-12) << i;
  }
}

// The lateral mixing's mean velocity (docs/mudflow.md section 4): the neighbours' velocities with
// the density's weights, the particle's own left out, so a faster column among neighbours of one
// velocity has exactly theirs as its mean, whatever its own.
TEST(FlowForces, TheMeanVelocityIsTheNeighboursWithTheDensitysWeights) {
  ParticleSet p;
  for (int k = 0; k < 5; ++k) p.add(500.0, {0.3 * k, 0.0, 0.0}, {2.0, 1.0, 0.0}, 1.0);
  p.vx[2] = 6.0;  // the middle column runs faster
  Evaluated e = evaluate(p);
  FlowForceConstants mixing{kRho, kG, 0.0};
  mixing.mean_velocity = true;
  const Eigen::Vector3d middle = flow_acceleration(p, 2, e.lists[2], e.normals, mixing).mean_velocity;
  EXPECT_NEAR((middle - Eigen::Vector3d(2.0, 1.0, 0.0)).norm(), 0.0, 1e-9);
  // Neighbours of two velocities: the mean lies between them, nearer the nearer neighbours'.
  p.vx[1] = p.vx[3] = 4.0;
  const Eigen::Vector3d mixed = flow_acceleration(p, 2, e.lists[2], e.normals, mixing).mean_velocity;
  EXPECT_GT(mixed.x(), 3.0);
  EXPECT_LT(mixed.x(), 4.0);
  EXPECT_NEAR(mixed.y(), 1.0, 1e-9);
  // Without the option no mean is measured.
  const FlowForceConstants plain{kRho, kG, 0.0};
  EXPECT_EQ(flow_acceleration(p, 2, e.lists[2], e.normals, plain).mean_velocity, Eigen::Vector3d::Zero());
}

TEST(FlowForces, GravityAloneIsItsTangentialPartOnASlope) {
  // One column on a plane of slope 30 degrees: g sin(30) down the slope, nothing normal.
  const double theta = std::acos(-1.0) / 6.0;
  ParticleSet p;
  p.add(500.0, {0.0, 0.0, 0.0}, {0, 0, 0}, 1.0);
  p.density[0] = 100.0;
  FootNormals normals;
  normals.resize(1);
  normals.x[0] = std::sin(theta);  // the ground falls towards +x
  normals.y[0] = 0.0;
  normals.z[0] = std::cos(theta);
  const Eigen::Vector3d a = flow_acceleration(p, 0, {}, normals, {kRho, kG, 0.5}).acceleration;
  EXPECT_NEAR(a.norm(), kG * std::sin(theta), 1e-12);
  EXPECT_NEAR(a.dot(normals.at(0)), 0.0, 1e-12);
  EXPECT_GT(a.x(), 0.0);
  EXPECT_LT(a.z(), 0.0);
}

TEST(FlowForces, TheVerticalColumnsPressurePushesOneOverCosSquaredHarderOnASlope) {
  // The depth ramp of the first test turned across a plane of slope 30 degrees that falls towards
  // +x: the vertical column h_v = sigma / rho0 grows as 1 + 0.05 y. The thin-layer pressure gives
  // -g cos^2(theta) dh_v/dy along y, the vertical column's (com1DFA's sphOption 1) -g dh_v/dy.
  const double theta = std::acos(-1.0) / 6.0, spacing = 0.5, slope = 0.05;
  ParticleSet p;
  for (int a = 0; a < 20; ++a) {
    for (int b = 0; b < 40; ++b) {
      const double y = b * spacing;
      p.add(kRho * (1.0 + slope * y) * spacing * spacing, {a * spacing, y, 0.0}, {0, 0, 0}, kSupportPerSpacing * spacing);
    }
  }
  Evaluated e = evaluate(p);
  for (std::size_t i = 0; i < p.size(); ++i) {
    e.normals.x[i] = std::sin(theta);
    e.normals.y[i] = 0.0;
    e.normals.z[i] = std::cos(theta);
  }
  FlowForceConstants thin_layer{kRho, kG, 0.0, PressureColumn::normal};
  FlowForceConstants vertical{kRho, kG, 0.0, PressureColumn::vertical};
  const double cos2 = std::cos(theta) * std::cos(theta);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const int a = static_cast<int>(i / 40), b = static_cast<int>(i % 40);
    if (std::min({a, b, 19 - a, 39 - b}) < 4) continue;
    const double normal_y = flow_acceleration(p, i, e.lists[i], e.normals, thin_layer).acceleration.y();
    const double vertical_y = flow_acceleration(p, i, e.lists[i], e.normals, vertical).acceleration.y();
    EXPECT_NEAR(normal_y, -kG * cos2 * slope, 0.05 * kG * cos2 * slope) << i;
    EXPECT_NEAR(vertical_y, -kG * slope, 0.05 * kG * slope) << i;
    EXPECT_NEAR(vertical_y * cos2, normal_y, 1e-12 * kG * slope) << i;
  }
}

TEST(FlowForces, ClosingSpeedIsTheFastestApproachOfANeighbour) {
  ParticleSet p;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  p.add(1.0, zero, {10.0, 0.0, 0.0}, 1.0);
  p.add(1.0, {2.0, 0.0, 0.0}, {7.0, 0.0, 0.0}, 1.0);    // ahead and slower: closes at 3 m/s
  p.add(1.0, {-2.0, 0.0, 0.0}, {9.0, 0.0, 0.0}, 1.0);   // behind and slower: recedes
  p.add(1.0, {0.0, 2.0, 0.0}, {10.0, -1.0, 0.0}, 1.0);  // beside, drawing near at 1 m/s
  p.add(1.0, zero, {0.0, 0.0, 0.0}, 1.0);               // on the same spot: no direction
  for (std::size_t i = 0; i < p.size(); ++i) p.density[i] = 1.0;
  FootNormals normals;
  normals.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) normals.z[i] = 1.0;
  const FlowForceConstants constants{kRho, kG, 0.5};
  const auto closing = [&](const NeighbourList& neighbours) {
    return flow_acceleration(p, 0, neighbours, normals, constants).closing_speed;
  };
  EXPECT_DOUBLE_EQ(closing({{1, 0.0}, {2, 0.0}, {3, 0.0}, {4, 0.0}}), 3.0);
  EXPECT_DOUBLE_EQ(closing({{3, 0.0}}), 1.0);
  EXPECT_DOUBLE_EQ(closing({{2, 0.0}, {4, 0.0}}), 0.0);
  // Moving together at any speed, nothing closes in.
  for (std::size_t i = 0; i < p.size(); ++i) {
    p.vx[i] = 40.0;
    p.vy[i] = 0.0;
  }
  EXPECT_DOUBLE_EQ(closing({{1, 0.0}, {2, 0.0}, {3, 0.0}}), 0.0);
}

TEST(FlowForces, PressureColumnsAreParsedByName) {
  EXPECT_EQ(parse_pressure_column("normal"), PressureColumn::normal);
  EXPECT_EQ(parse_pressure_column("vertical"), PressureColumn::vertical);
  EXPECT_STREQ(to_string(PressureColumn::vertical), "vertical");
  EXPECT_THROW(parse_pressure_column("hydrostatic"), InputError);
}

}  // namespace
}  // namespace talus
