// Tests of the contact of the columns with the bilinear ground (paper 2.2, 4.1; docs/mudflow.md
// "Ground contact").
#include "talus/mudflow/surface_following.hpp"

#include <cmath>

#include <gtest/gtest.h>

#include "../../validation/synthetic_ground.hpp"

namespace talus {
namespace {

using testing_ground::fast_material;
using testing_ground::local_spec;
using testing_ground::make_ground;

// A plane falling at 0.4 towards +x over x in [0, 99] m, y in [-99, 0] m.
GroundModel plane() {
  return make_ground(local_spec(100, 100, 1.0), [](double x, double) { return 100.0 - 0.4 * x; },
                     fast_material(0, 0, 0.5));
}

TEST(SurfaceFollowing, DriftKeepsTheFootOnTheGroundAndTheSpeed) {
  const GroundModel ground = plane();
  ParticleSet p;
  p.add(1.0, {10.0, -50.0, 0.0}, {3.0, 1.0, 0.0}, 1.0);
  FootNormals normals;
  normals.resize(1);
  place_on_ground(ground, p, 0, normals);
  const double speed = p.velocity(0).norm();
  EXPECT_NEAR(p.z[0], 96.0, 1e-12);
  EXPECT_NEAR(p.velocity(0).dot(normals.at(0)), 0.0, 1e-12);
  EXPECT_NEAR(speed, std::hypot(3.0, 1.0), 1e-12);  // turned, not shortened
  for (int k = 0; k < 10; ++k) ASSERT_TRUE(drift_on_ground(ground, p, 0, 0.5, normals));
  EXPECT_NEAR(p.z[0], ground.elevation(p.x[0], p.y[0]), 1e-12);
  EXPECT_NEAR(p.velocity(0).norm(), speed, 1e-12);
  EXPECT_NEAR(normals.z[0], 1.0 / std::sqrt(1.16), 1e-12);  // cos(theta), tan(theta) = 0.4
}

TEST(SurfaceFollowing, LeavingTheValidAreaIsReportedAndTheParticleStays) {
  const GroundModel ground = plane();
  ParticleSet p;
  p.add(1.0, {98.5, -50.0, 0.0}, {10.0, 0.0, 0.0}, 1.0);
  FootNormals normals;
  normals.resize(1);
  place_on_ground(ground, p, 0, normals);
  const Eigen::Vector3d before = p.position(0);
  EXPECT_FALSE(drift_on_ground(ground, p, 0, 1.0, normals));
  EXPECT_EQ(p.position(0), before);
  p.vx[0] = std::nan("");
  EXPECT_FALSE(drift_on_ground(ground, p, 0, 1.0, normals));
}

TEST(SurfaceFollowing, TurnedIntoPlaneKeepsLengthAndLiesInThePlane) {
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.2, 1.0).normalized();
  const Eigen::Vector3d v(2.0, 1.0, -0.5);
  const Eigen::Vector3d turned = turned_into_plane(v, n);
  EXPECT_NEAR(turned.norm(), v.norm(), 1e-12);
  EXPECT_NEAR(turned.dot(n), 0.0, 1e-12);
  EXPECT_NEAR(tangent_part(v, n).dot(n), 0.0, 1e-12);
}

// Node normals (`[contact] node_normals`, com1DFA's): on a plane they are the plane's normal; on
// a curved ground they turn continuously across a node line, where the squares' own normals jump,
// and they agree with the surface's slope at the node (its central differences there).
TEST(SurfaceFollowing, NodeNormalsAreContinuousAcrossNodeLines) {
  const GroundModel flat = plane();
  const NodeSlopes flat_slopes(flat);
  const NodeSquare inside = flat.locate(30.4, -40.7);
  EXPECT_NEAR((ground_normal(flat, inside, &flat_slopes) - ground_normal(flat, inside)).norm(), 0.0, 1e-12);
  // z = x^2 / 20 on 1 m cells: the squares' slopes along x differ by 0.1 from one to the next
  // (1.95 and 2.05 on either side of x = 20 m, normals 0.02 apart).
  const GroundModel bowl = make_ground(local_spec(40, 40, 1.0), [](double x, double) { return x * x / 20.0; },
                                       fast_material(0, 0, 0.5));
  const NodeSlopes slopes(bowl);
  const double line = 20.0;  // a node line x = 20 m
  const NodeSquare before = bowl.locate(line - 1e-9, -20.5), after = bowl.locate(line + 1e-9, -20.5);
  EXPECT_GT((ground_normal(bowl, before) - ground_normal(bowl, after)).norm(), 0.015);
  EXPECT_LT((ground_normal(bowl, before, &slopes) - ground_normal(bowl, after, &slopes)).norm(), 1e-8);
  const Eigen::Vector3d at_node = ground_normal(bowl, bowl.locate(line, -20.0), &slopes);
  EXPECT_NEAR(-at_node.x() / at_node.z(), line / 10.0, 1e-9);  // dz/dx = x / 10
  // Where a node of the stencil is off the valid area, the square's own normal is kept.
  const NodeSquare edge = bowl.locate(0.3, -20.5);
  EXPECT_EQ(ground_normal(bowl, edge, &slopes), ground_normal(bowl, edge));
}

TEST(SurfaceFollowing, CurvatureOfAHollowAndOfACrest) {
  // z = +-x^2 / (2 rho) with rho = 50 m: curvature 1/rho at x = 0 along x, none along y.
  const double rho = 50.0;
  const GridSpec spec = local_spec(81, 81, 0.5);
  const GroundModel hollow = make_ground(spec, [&](double x, double) { return (x - 20) * (x - 20) / (2 * rho); },
                                         fast_material(0, 0, 0.5));
  const GroundModel crest = make_ground(spec, [&](double x, double) { return -(x - 20) * (x - 20) / (2 * rho); },
                                        fast_material(0, 0, 0.5));
  const Eigen::Vector3d along_x(1, 0, 0), along_y(0, 1, 0);
  // 2%: the bilinear surface bends only at node lines, averaged over the 2 m span.
  EXPECT_NEAR(curvature_along(hollow, 20.0, -20.0, along_x, 1.0), 1.0 / rho, 0.02 / rho);
  EXPECT_NEAR(curvature_along(crest, 20.0, -20.0, along_x, 1.0), -1.0 / rho, 0.02 / rho);
  EXPECT_NEAR(curvature_along(hollow, 20.0, -20.0, along_y, 1.0), 0.0, 1e-12);
  EXPECT_EQ(curvature_along(hollow, 20.0, -20.0, Eigen::Vector3d(0, 0, 1), 1.0), 0.0);
}

TEST(SurfaceFollowing, TheStepNormalIsTheMeanOfTheFootsAndTheOneAhead) {
  // On a plane the normal ahead is the foot's; across a kink from a 0.4 slope to a flat, the mean
  // of the two, normalised; off the DEM the foot's alone.
  const GroundModel flat_plane = plane();
  const NodeSquare square = flat_plane.locate(10.0, -50.0);
  const Eigen::Vector3d foot = ground_normal(flat_plane, square);
  const Eigen::Vector3d same =
      step_averaged_normal(flat_plane, foot, 10.0, -50.0, Eigen::Vector3d(3.0, 1.0, -1.2), 2.0);
  EXPECT_NEAR((same - foot).norm(), 0.0, 1e-12);
  const GroundModel kink = make_ground(local_spec(100, 100, 1.0),
                                       [](double x, double) { return x < 50.0 ? 100.0 - 0.4 * x : 80.0; },
                                       fast_material(0, 0, 0.5));
  const Eigen::Vector3d before = ground_normal(kink, kink.locate(45.5, -50.5));
  const Eigen::Vector3d across = step_averaged_normal(kink, before, 45.5, -50.5, Eigen::Vector3d(5.0, 0.0, -2.0), 2.0);
  const Eigen::Vector3d expected = (before + Eigen::Vector3d(0.0, 0.0, 1.0)).normalized();
  EXPECT_NEAR((across - expected).norm(), 0.0, 1e-12);
  EXPECT_NEAR(across.norm(), 1.0, 1e-12);
  EXPECT_EQ(step_averaged_normal(kink, before, 45.5, -50.5, Eigen::Vector3d(500.0, 0.0, 0.0), 1.0), before);
}

}  // namespace
}  // namespace talus
