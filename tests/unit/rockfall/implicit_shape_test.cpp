// Tests of the rock's implicit surface (paper 3.1): the normalised radial function and its
// gradient, the Fibonacci-ray surface samples and their areas, cuts (paper fig. 4), shifts, and
// the world bounds and bounding radius, against closed forms and densely sampled references.
#include "talus/rockfall/implicit_shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

namespace talus {
namespace {

Rock make_rock(BlockShape shape, const Eigen::Vector3d& axes) {
  Rock rock;
  rock.shape = shape;
  rock.axes = axes;
  return rock;
}

const Eigen::Vector3d kAxes(2.0, 1.4, 0.8);  // m: full axes of the ellipsoid and the box

Eigen::Quaterniond random_orientation(std::mt19937& random) {
  std::normal_distribution<double> normal;
  return Eigen::Quaterniond(Eigen::Vector4d(normal(random), normal(random), normal(random), normal(random))).normalized();
}

// Largest distance (m) from the local origin over a shape's samples.
double farthest_sample(const ImplicitShape& shape) {
  double farthest = 0.0;
  for (const SurfaceSample& sample : shape.surface()) farthest = std::max(farthest, sample.position.norm());
  return farthest;
}

TEST(ImplicitShape, SphereValueIsDistanceOverRadius) {
  const ImplicitShape sphere(make_rock(BlockShape::sphere, Eigen::Vector3d(2.0, 9.0, 9.0)));  // r = 1 m
  // f = |p| / r - 1 exactly (to rounding, 1e-15).
  EXPECT_NEAR(sphere.value(Eigen::Vector3d::Zero()), -1.0, 1e-15);
  EXPECT_NEAR(sphere.value(Eigen::Vector3d(0.3, -0.4, 0.0)), -0.5, 1e-15);
  EXPECT_NEAR(sphere.value(Eigen::Vector3d(0.0, 0.0, 2.0)), 1.0, 1e-15);
  EXPECT_TRUE(sphere.inside(Eigen::Vector3d(0.0, 0.99, 0.0)));
  EXPECT_FALSE(sphere.inside(Eigen::Vector3d(0.0, 1.01, 0.0)));
}

TEST(ImplicitShape, EllipsoidAndBoxVanishOnTheirSurfaces) {
  const Eigen::Vector3d s = 0.5 * kAxes;
  const ImplicitShape ellipsoid(make_rock(BlockShape::ellipsoid, kAxes));
  const ImplicitShape box(make_rock(BlockShape::box, kAxes));
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d tip = s[i] * Eigen::Vector3d::Unit(i);
    EXPECT_NEAR(ellipsoid.value(tip), 0.0, 1e-15);
    EXPECT_NEAR(box.value(-tip), 0.0, 1e-15);
    // Half way to the surface along an axis: f = -1/2 for both (homogeneous of degree 1).
    EXPECT_NEAR(ellipsoid.value(0.5 * tip), -0.5, 1e-15);
    EXPECT_NEAR(box.value(0.5 * tip), -0.5, 1e-15);
  }
  // The superellipsoid's diagonal point 3^(-1/8) (a, b, c) lies on it; the box corner lies
  // outside at f = 3^(1/8) - 1 = 0.147, while the ellipsoid's value there is sqrt(3) - 1.
  EXPECT_NEAR(box.value(std::pow(3.0, -1.0 / 8.0) * s), 0.0, 1e-14);
  EXPECT_NEAR(box.value(s), std::pow(3.0, 1.0 / 8.0) - 1.0, 1e-14);
  EXPECT_NEAR(ellipsoid.value(s), std::sqrt(3.0) - 1.0, 1e-14);
}

TEST(ImplicitShape, GradientMatchesFiniteDifferences) {
  std::mt19937 random(7);
  std::uniform_real_distribution<double> coordinate(-1.2, 1.2);
  const double step = 1e-6;  // m
  for (const BlockShape kind : {BlockShape::sphere, BlockShape::ellipsoid, BlockShape::box}) {
    const ImplicitShape shape(make_rock(kind, kAxes));
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random));
      Eigen::Vector3d numeric;
      for (int i = 0; i < 3; ++i) {
        const Eigen::Vector3d h = step * Eigen::Vector3d::Unit(i);
        numeric[i] = (shape.value(p + h) - shape.value(p - h)) / (2.0 * step);
      }
      // Central differences of a smooth function: 1e-6 of the gradient's size.
      EXPECT_LT((shape.gradient(p) - numeric).norm(), 1e-6 * numeric.norm()) << static_cast<int>(kind);
    }
  }
  // A cut takes the gradient of the active piece: the plane's n / r beyond it, the sphere's
  // p / (r |p|) where the sphere is the nearer surface (r = 1 m).
  const ImplicitShape half = ImplicitShape(make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(2.0)))
                                 .cut({Eigen::Vector3d::UnitZ(), 0.0});
  EXPECT_LT((half.gradient(Eigen::Vector3d(0.1, 0.0, 0.3)) - Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  EXPECT_LT((half.gradient(Eigen::Vector3d(0.0, 0.0, -0.9)) + Eigen::Vector3d::UnitZ()).norm(), 1e-15);
  EXPECT_NEAR(half.value(Eigen::Vector3d(0.1, 0.0, 0.3)), 0.3, 1e-15);
}

TEST(ImplicitShape, SamplesLieOnTheSurfaceWithUnitOutwardNormals) {
  const ImplicitShape box(make_rock(BlockShape::box, kAxes));
  const ImplicitShape sphere(make_rock(BlockShape::sphere, kAxes));
  const std::vector<ImplicitShape> shapes = {
      ImplicitShape(make_rock(BlockShape::ellipsoid, kAxes), 300), box, sphere.cut({Eigen::Vector3d::UnitZ(), 0.2}),
      box.cut({Eigen::Vector3d(1.0, 1.0, 1.0), 0.1}).cut({Eigen::Vector3d(0.0, -1.0, 2.0), 0.05})};
  for (const ImplicitShape& shape : shapes) {
    ASSERT_FALSE(shape.surface().empty());
    // Every part is convex and holds the centre of its samples' area, so every normal points away from it.
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    for (const SurfaceSample& sample : shape.surface()) centre += sample.area * sample.position;
    centre /= shape.surface_area();
    for (const SurfaceSample& sample : shape.surface()) {
      EXPECT_NEAR(shape.value(sample.position), 0.0, 1e-10);  // bisected to 1e-12 of the distance
      EXPECT_NEAR(sample.normal.norm(), 1.0, 1e-12);
      EXPECT_GT(sample.normal.dot(sample.position - centre), 0.0);
      EXPECT_GT(sample.area, 0.0);
    }
  }
  EXPECT_EQ(shapes[0].surface().size(), 300u);
  EXPECT_EQ(shapes[1].surface().size(), 256u);
}

TEST(ImplicitShape, SurfaceAreasMatchClosedForms) {
  // Sphere at 256 samples: 4 pi r^2 (required within 1%; every sample stands for exactly
  // r^2 4 pi / N, so it is exact to rounding).
  const ImplicitShape sphere(make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(1.5)));
  EXPECT_NEAR(sphere.surface_area() / (4.0 * std::numbers::pi * 0.75 * 0.75), 1.0, 1e-12);
  // Ellipsoid (Legendre's elliptic-integral form) within 0.1% (measured 3e-7).
  const double a = 1.0, b = 0.7, c = 0.4;
  const double phi = std::acos(c / a);
  const double k = std::sqrt(a * a * (b * b - c * c) / (b * b * (a * a - c * c)));
  const double area = 2.0 * std::numbers::pi * c * c +
                      2.0 * std::numbers::pi * a * b / std::sin(phi) *
                          (std::ellint_2(k, phi) * std::sin(phi) * std::sin(phi) +
                           std::ellint_1(k, phi) * std::cos(phi) * std::cos(phi));
  EXPECT_NEAR(ImplicitShape(make_rock(BlockShape::ellipsoid, kAxes)).surface_area() / area, 1.0, 1e-3);
  // Hemisphere: 2 pi r^2 curved + pi r^2 flat, within 3% (measured 1.45% cut across x, 0.19%
  // across z: the area jumps at the rim, which the rays resolve to about their spacing).
  const ImplicitShape sphere_1m(make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(1.0)));
  for (const int axis : {0, 2}) {
    const ImplicitShape half = sphere_1m.cut({Eigen::Vector3d::Unit(axis), 0.0});
    EXPECT_NEAR(half.surface_area() / (3.0 * std::numbers::pi * 0.25), 1.0, 3e-2) << axis;
  }
  // Box superellipsoid: no closed form; 256 samples within 1% of 20000 (measured 0.25%).
  const double coarse = ImplicitShape(make_rock(BlockShape::box, kAxes)).surface_area();
  const double fine = ImplicitShape(make_rock(BlockShape::box, kAxes), 20000).surface_area();
  EXPECT_NEAR(coarse / fine, 1.0, 1e-2);
}

TEST(ImplicitShape, CutSamplesFromInsideThePartEvenWhenTheOriginIsOutside) {
  // The cap x <= -0.3 m of a sphere of r = 1 m: the local origin lies outside it. Area: the
  // cap's 2 pi r h with h = 0.7 m plus the disc pi (r^2 - 0.3^2); within 3% (measured 1.6%, the
  // rim as for the hemisphere).
  const ImplicitShape sphere(make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(2.0)));
  const ImplicitShape cap = sphere.cut({Eigen::Vector3d::UnitX(), -0.3});
  EXPECT_FALSE(cap.inside(Eigen::Vector3d::Zero()));
  EXPECT_TRUE(cap.inside(Eigen::Vector3d(-0.5, 0.0, 0.0)));
  for (const SurfaceSample& sample : cap.surface()) {
    EXPECT_NEAR(cap.value(sample.position), 0.0, 1e-10);
    EXPECT_LE(sample.position.x(), -0.3 + 1e-9);
  }
  const double expected = 2.0 * std::numbers::pi * 0.7 + std::numbers::pi * (1.0 - 0.09);
  EXPECT_NEAR(cap.surface_area() / expected, 1.0, 3e-2);
  // A non-unit normal names the same half-space.
  const ImplicitShape same = sphere.cut({Eigen::Vector3d(4.0, 0.0, 0.0), -1.2});
  EXPECT_NEAR(same.surface_area(), cap.surface_area(), 1e-12);
  // Nothing left, or no plane at all.
  EXPECT_THROW(sphere.cut({Eigen::Vector3d::UnitX(), -1.5}), std::invalid_argument);
  EXPECT_THROW(sphere.cut({Eigen::Vector3d::Zero(), 0.0}), std::invalid_argument);
  EXPECT_THROW(ImplicitShape(make_rock(BlockShape::sphere, Eigen::Vector3d::Ones()), 0), std::invalid_argument);
}

TEST(ImplicitShape, ShiftedMovesTheOriginTheSamplesAndLaterCuts) {
  const ImplicitShape box(make_rock(BlockShape::box, kAxes));
  const Eigen::Vector3d origin(0.2, -0.1, 0.05);
  const ImplicitShape moved = box.shifted(origin);
  std::mt19937 random(3);
  std::uniform_real_distribution<double> coordinate(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random));
    EXPECT_NEAR(moved.value(p), box.value(p + origin), 1e-15);
    EXPECT_LT((moved.gradient(p) - box.gradient(p + origin)).norm(), 1e-12);
  }
  ASSERT_EQ(moved.surface().size(), box.surface().size());
  for (std::size_t i = 0; i < box.surface().size(); ++i) {
    EXPECT_LT((moved.surface()[i].position - (box.surface()[i].position - origin)).norm(), 1e-15);
    EXPECT_EQ(moved.surface()[i].area, box.surface()[i].area);
  }
  // A cut after a shift is given in the shifted frame: n.p <= d there is n.p <= d + n.o before.
  const CutPlane plane{Eigen::Vector3d(0.6, 0.0, 0.8), 0.1};
  const ImplicitShape cut_after = moved.cut(plane);
  const ImplicitShape cut_before = box.cut({plane.normal, plane.offset + plane.normal.dot(origin)}).shifted(origin);
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::Vector3d p(coordinate(random), coordinate(random), coordinate(random));
    EXPECT_NEAR(cut_after.value(p), cut_before.value(p), 1e-14);
  }
  EXPECT_NEAR(cut_after.surface_area(), cut_before.surface_area(), 1e-9);
}

TEST(ImplicitShape, WorldBoundsOfUncutShapesAreExact) {
  std::mt19937 random(11);
  const Eigen::Vector3d s = 0.5 * kAxes;
  const ImplicitShape ellipsoid(make_rock(BlockShape::ellipsoid, kAxes));
  const ImplicitShape box(make_rock(BlockShape::box, kAxes));
  const ImplicitShape dense_box(make_rock(BlockShape::box, kAxes), 40000);
  const Eigen::Vector3d origin(0.3, 0.1, -0.2);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::Quaterniond q = random_orientation(random);
    const Eigen::Matrix3d r = q.toRotationMatrix();
    // Ellipsoid: half size sqrt(sum_i (R_ji s_i)^2) along world axis j (to rounding, 1e-12 m);
    // shifted, the box moves to -R o with the same size.
    const Eigen::AlignedBox3d bounds = ellipsoid.shifted(origin).world_bounds(q);
    for (int j = 0; j < 3; ++j) {
      const double half = r.row(j).transpose().cwiseProduct(s).norm();
      EXPECT_NEAR(bounds.max()[j], half - (r * origin)[j], 1e-12);
      EXPECT_NEAR(bounds.min()[j], -half - (r * origin)[j], 1e-12);
    }
    // Box: never below the farthest of 40000 samples, and within 0.5% of the bounding radius
    // above it (measured 0.06%, the samples' own shortfall at the rounded corners).
    const Eigen::AlignedBox3d box_bounds = box.world_bounds(q);
    Eigen::AlignedBox3d sampled;
    for (const SurfaceSample& sample : dense_box.surface()) sampled.extend(r * sample.position);
    for (int j = 0; j < 3; ++j) {
      EXPECT_GE(box_bounds.max()[j], sampled.max()[j]);
      EXPECT_LE(box_bounds.max()[j], sampled.max()[j] + 5e-3 * box.bounding_radius());
      EXPECT_LE(box_bounds.min()[j], sampled.min()[j]);
      EXPECT_GE(box_bounds.min()[j], sampled.min()[j] - 5e-3 * box.bounding_radius());
    }
  }
}

TEST(ImplicitShape, WorldBoundsOfCutShapesEncloseThePart) {
  std::mt19937 random(5);
  const ImplicitShape sphere(make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(2.0)));
  const ImplicitShape box(make_rock(BlockShape::box, kAxes));
  const CutPlane diagonal{Eigen::Vector3d(1.0, 1.0, 1.0).normalized(), 0.1};
  const std::vector<CutPlane> quarter = {{Eigen::Vector3d::UnitZ(), 0.0}, {Eigen::Vector3d::UnitX(), 0.0}};
  const ImplicitShape parts[] = {sphere.cut(quarter[0]).cut(quarter[1]), box.cut(diagonal)};
  const ImplicitShape dense_parts[] = {
      ImplicitShape(make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(2.0)), 40000).cut(quarter[0]).cut(quarter[1]),
      ImplicitShape(make_rock(BlockShape::box, kAxes), 40000).cut(diagonal)};
  // Shifted well off the parts' centres, so that the bounds' shift is exercised too.
  const Eigen::Vector3d origin(-0.2, 0.1, -0.3);
  for (int k = 0; k < 2; ++k) {
    const ImplicitShape part = parts[k].shifted(origin);
    const ImplicitShape dense = dense_parts[k].shifted(origin);
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::Quaterniond q = random_orientation(random);
      const Eigen::Matrix3d r = q.toRotationMatrix();
      const Eigen::AlignedBox3d bounds = part.world_bounds(q);
      Eigen::AlignedBox3d sampled;
      for (const SurfaceSample& sample : dense.surface()) sampled.extend(r * sample.position);
      // Conservative (it encloses every dense sample), and within 8% of the bounding radius of
      // the densely sampled box on each side (measured up to 2.3% for the quarter sphere and
      // 3.5% for the cut box: the interpolated support function's looseness).
      const double tolerance = 0.08 * part.bounding_radius();
      for (int j = 0; j < 3; ++j) {
        EXPECT_GE(bounds.max()[j], sampled.max()[j]) << k;
        EXPECT_LE(bounds.min()[j], sampled.min()[j]) << k;
        EXPECT_LE(bounds.max()[j], sampled.max()[j] + tolerance) << k;
        EXPECT_GE(bounds.min()[j], sampled.min()[j] - tolerance) << k;
      }
    }
  }
}

TEST(ImplicitShape, BoundingRadiusEnclosesEverySurfacePoint) {
  // Centred uncut shapes: exact. Sphere r; ellipsoid its largest semi-axis; cube superellipsoid
  // of half side s: its diagonal point 3^(3/8) s (to rounding, 1e-12 m).
  EXPECT_NEAR(ImplicitShape(make_rock(BlockShape::sphere, Eigen::Vector3d::Constant(1.2))).bounding_radius(), 0.6, 1e-15);
  EXPECT_NEAR(ImplicitShape(make_rock(BlockShape::ellipsoid, kAxes)).bounding_radius(), 1.0, 1e-15);
  EXPECT_NEAR(ImplicitShape(make_rock(BlockShape::box, Eigen::Vector3d::Constant(2.0))).bounding_radius(),
              std::pow(3.0, 3.0 / 8.0), 1e-12);
  // Box of unequal sides: at least its farthest of 40000 samples, within 0.5% above (measured
  // 0.002%).
  const ImplicitShape box(make_rock(BlockShape::box, kAxes));
  const double farthest_box = farthest_sample(ImplicitShape(make_rock(BlockShape::box, kAxes), 40000));
  EXPECT_GE(box.bounding_radius(), farthest_box);
  EXPECT_LE(box.bounding_radius(), 1.005 * farthest_box);
  // Shifted and cut shapes: a guaranteed bound, within 8% above the farthest dense sample
  // (measured 2.8%), and never above |shift| + the uncut radius.
  const CutPlane plane{Eigen::Vector3d(1.0, 0.3, -0.5).normalized(), 0.2};
  const Eigen::Vector3d origin(0.1, -0.2, 0.15);
  const ImplicitShape parts[] = {box.shifted(origin), box.cut(plane).shifted(origin)};
  const ImplicitShape dense[] = {ImplicitShape(make_rock(BlockShape::box, kAxes), 40000).shifted(origin),
                                 ImplicitShape(make_rock(BlockShape::box, kAxes), 40000).cut(plane).shifted(origin)};
  for (int k = 0; k < 2; ++k) {
    const double farthest = farthest_sample(dense[k]);
    EXPECT_GE(parts[k].bounding_radius(), farthest) << k;
    EXPECT_LE(parts[k].bounding_radius(), 1.08 * farthest) << k;
    EXPECT_LE(parts[k].bounding_radius(), origin.norm() + box.bounding_radius()) << k;
  }
}

}  // namespace
}  // namespace talus
