// Tests of the rock's closed forms (paper 3.1): volume, mass, inertia, bounding-box half height
// and frontal area of the sphere, the ellipsoid and the box (superellipsoid of exponent 8),
// against the textbook formulas and brute-force integration and sampling.
#include "talus/rockfall/rock.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace talus {
namespace {

Rock make_rock(BlockShape shape, const Eigen::Vector3d& axes, double density = 2700.0) {
  Rock rock;
  rock.shape = shape;
  rock.axes = axes;
  rock.density = density;
  return rock;
}

bool inside(const Rock& rock, const Eigen::Vector3d& x) {
  const Eigen::Vector3d s = 0.5 * rock.axes;
  if (rock.shape == BlockShape::box) {
    double sum = 0.0;
    for (int i = 0; i < 3; ++i) sum += std::pow(std::abs(x[i] / s[i]), kBoxExponent);
    return sum <= 1.0;
  }
  return x.cwiseQuotient(s).squaredNorm() <= 1.0;
}

// Midpoint-rule volume and second moments (integral of x_i^2 dV) over the bounding box.
struct Moments {
  double volume = 0;
  Eigen::Vector3d second = Eigen::Vector3d::Zero();
};
Moments integrate(const Rock& rock, int n) {
  const Eigen::Vector3d s = 0.5 * rock.axes;
  const Eigen::Vector3d h = rock.axes / n;
  Moments m;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        const Eigen::Vector3d x(-s.x() + (i + 0.5) * h.x(), -s.y() + (j + 0.5) * h.y(), -s.z() + (k + 0.5) * h.z());
        if (!inside(rock, x)) continue;
        const double dv = h.prod();
        m.volume += dv;
        m.second += dv * x.cwiseProduct(x);
      }
    }
  }
  return m;
}

// The lowest point below the centre over a dense sampling of the surface (superquadric
// parametrisation; exponent 2 is the ellipsoid).
double sampled_half_height(const Rock& rock, const Eigen::Quaterniond& q) {
  const double p = rock.shape == BlockShape::box ? kBoxExponent : 2.0;
  const Eigen::Vector3d s = 0.5 * rock.axes;
  const Eigen::Matrix3d r = q.toRotationMatrix();
  const auto signed_power = [p](double c) { return std::copysign(std::pow(std::abs(c), 2.0 / p), c); };
  double lowest = 0.0;
  const int n = 300;
  for (int i = 0; i <= n; ++i) {
    const double eta = -0.5 * std::numbers::pi + std::numbers::pi * i / n;
    for (int j = 0; j < 2 * n; ++j) {
      const double omega = std::numbers::pi * j / n;
      const Eigen::Vector3d x(s.x() * signed_power(std::cos(eta) * std::cos(omega)),
                              s.y() * signed_power(std::cos(eta) * std::sin(omega)), s.z() * signed_power(std::sin(eta)));
      lowest = std::min(lowest, (r * x).z());
    }
  }
  return -lowest;
}

TEST(Rock, SphereClosedForms) {
  const Rock rock = make_rock(BlockShape::sphere, Eigen::Vector3d(1.2, 9.0, 9.0));  // diameter: axes.x()
  const double r = 0.6;
  EXPECT_NEAR(rock.volume(), 4.0 / 3.0 * std::numbers::pi * r * r * r, 1e-12);
  EXPECT_NEAR(rock.mass(), 2700.0 * rock.volume(), 1e-9);
  const Eigen::Matrix3d inertia = rock.inertia();
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(inertia(i, i), 0.4 * rock.mass() * r * r, 1e-9);
  EXPECT_NEAR(inertia(0, 1), 0.0, 0.0);
  EXPECT_DOUBLE_EQ(rock.half_height(Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()))), r);
  EXPECT_NEAR(rock.frontal_area(), std::numbers::pi * r * r, 1e-12);
  EXPECT_DOUBLE_EQ(rock.bounding_radius(), r);
}

TEST(Rock, EllipsoidMassInertiaAndHalfHeight) {
  const Rock rock = make_rock(BlockShape::ellipsoid, Eigen::Vector3d(2.0, 1.0, 0.5));
  const double a = 1.0, b = 0.5, c = 0.25;
  EXPECT_NEAR(rock.volume(), 4.0 / 3.0 * std::numbers::pi * a * b * c, 1e-12);
  const double m = rock.mass();
  const Eigen::Matrix3d inertia = rock.inertia();
  EXPECT_NEAR(inertia(0, 0), m * (b * b + c * c) / 5.0, 1e-9);
  EXPECT_NEAR(inertia(1, 1), m * (a * a + c * c) / 5.0, 1e-9);
  EXPECT_NEAR(inertia(2, 2), m * (a * a + b * b) / 5.0, 1e-9);
  // Numerical check of the same closed forms.
  const Moments moments = integrate(rock, 120);
  EXPECT_NEAR(moments.volume / rock.volume(), 1.0, 2e-3);
  EXPECT_NEAR(rock.density * (moments.second.y() + moments.second.z()) / inertia(0, 0), 1.0, 3e-3);

  EXPECT_NEAR(rock.half_height(Eigen::Quaterniond::Identity()), c, 1e-15);
  EXPECT_NEAR(rock.half_height(Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * std::numbers::pi, Eigen::Vector3d::UnitX()))),
              b, 1e-12);
  EXPECT_NEAR(rock.half_height(Eigen::Quaterniond(Eigen::AngleAxisd(0.5 * std::numbers::pi, Eigen::Vector3d::UnitY()))),
              a, 1e-12);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.4 + 0.9 * k, Eigen::Vector3d(1.0, -0.3 * k, 0.5 + k).normalized()));
    EXPECT_NEAR(rock.half_height(q), sampled_half_height(rock, q), 1e-3 * a);
  }
  EXPECT_DOUBLE_EQ(rock.bounding_radius(), a);
  const double r_eq = std::cbrt(a * b * c);
  EXPECT_NEAR(rock.frontal_area(), std::numbers::pi * r_eq * r_eq, 1e-12);
}

TEST(Rock, BoxIsASuperellipsoidOfExponentEight) {
  const Rock rock = make_rock(BlockShape::box, Eigen::Vector3d(2.0, 1.4, 0.8));
  const Eigen::Vector3d s(1.0, 0.7, 0.4);
  // 8 abc G(1 + 1/8)^3 / G(1 + 3/8) = 0.9396 of the box.
  EXPECT_NEAR(rock.volume() / (8.0 * s.prod()), 0.93959, 1e-4);
  const Moments moments = integrate(rock, 120);
  EXPECT_NEAR(moments.volume / rock.volume(), 1.0, 2e-3);
  const Eigen::Matrix3d inertia = rock.inertia();
  EXPECT_NEAR(rock.density * (moments.second.y() + moments.second.z()) / inertia(0, 0), 1.0, 3e-3);
  EXPECT_NEAR(rock.density * (moments.second.x() + moments.second.z()) / inertia(1, 1), 1.0, 3e-3);
  EXPECT_NEAR(rock.density * (moments.second.x() + moments.second.y()) / inertia(2, 2), 1.0, 3e-3);
  // Between the inscribed ellipsoid and the box: m (b^2 + c^2) / 5 < I_x < m (b^2 + c^2) / 3.
  const double m = rock.mass();
  EXPECT_GT(inertia(0, 0), m * (s.y() * s.y() + s.z() * s.z()) / 5.0);
  EXPECT_LT(inertia(0, 0), m * (s.y() * s.y() + s.z() * s.z()) / 3.0);

  EXPECT_NEAR(rock.half_height(Eigen::Quaterniond::Identity()), s.z(), 1e-12);
  for (int k = 0; k < 5; ++k) {
    const Eigen::Quaterniond q(Eigen::AngleAxisd(0.3 + 0.8 * k, Eigen::Vector3d(0.2 * k, 1.0, 0.7 - 0.2 * k).normalized()));
    const double h = rock.half_height(q);
    EXPECT_NEAR(h, sampled_half_height(rock, q), 2e-3);
    // Never lower than the inscribed ellipsoid's, never higher than the exact box's sum |R_zi| s_i.
    const Eigen::Vector3d row = q.toRotationMatrix().row(2).transpose();
    EXPECT_GE(h, row.cwiseProduct(s).norm() - 1e-12);
    EXPECT_LE(h, row.cwiseAbs().dot(s) + 1e-12);
  }
}

}  // namespace
}  // namespace talus
