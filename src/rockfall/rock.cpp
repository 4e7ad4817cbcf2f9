// A rock's shape, size and mass (paper 3.1): closed-form volume, inertia tensor, bounding-box
// half height and equivalent-sphere frontal area of a sphere, an ellipsoid, or a superellipsoid
// of exponent kBoxExponent standing for a box.
#include "talus/rockfall/rock.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace talus {
namespace {

// Semi-axes (m): the sphere's radius three times, else half the full axes.
Eigen::Vector3d semi_axes(const Rock& rock) {
  if (rock.shape == BlockShape::sphere) return Eigen::Vector3d::Constant(0.5 * rock.axes.x());
  return 0.5 * rock.axes;
}

// Superellipsoid sum |x_i / s_i|^p <= 1: volume = 8 s1 s2 s3 G(1+1/p)^3 / G(1+3/p) and the
// second moment per unit volume along axis i, s_i^2 G(1+3/p)^2 / (3 G(1+1/p) G(1+5/p)), from
// Dirichlet's integral. p = 2 gives the ellipsoid's 4/3 pi and s_i^2 / 5.
double superellipsoid_volume_factor(double p) {
  return 8.0 * std::pow(std::tgamma(1.0 + 1.0 / p), 3) / std::tgamma(1.0 + 3.0 / p);
}
double superellipsoid_moment_factor(double p) {
  const double g3 = std::tgamma(1.0 + 3.0 / p);
  return g3 * g3 / (3.0 * std::tgamma(1.0 + 1.0 / p) * std::tgamma(1.0 + 5.0 / p));
}

}  // namespace

// Paper 3.1 (rock mass): sphere 4/3 pi r^3, ellipsoid 4/3 pi a b c, box superellipsoid above.
double Rock::volume() const {
  const Eigen::Vector3d s = semi_axes(*this);
  const double product = s.x() * s.y() * s.z();
  if (shape == BlockShape::box) return superellipsoid_volume_factor(kBoxExponent) * product;
  return 4.0 / 3.0 * std::numbers::pi * product;
}

// Paper 3.1 (inertia tensor), about the centre in the local frame: I_x = m k (b^2 + c^2) and
// cyclic, with k = 1/5 for the sphere and ellipsoid and the superellipsoid's factor for the box.
Eigen::Matrix3d Rock::inertia() const {
  const Eigen::Vector3d s = semi_axes(*this);
  const double k = shape == BlockShape::box ? superellipsoid_moment_factor(kBoxExponent) : 0.2;
  const Eigen::Vector3d s2 = s.cwiseProduct(s);
  const double m = mass();
  return Eigen::Vector3d(m * k * (s2.y() + s2.z()), m * k * (s2.x() + s2.z()), m * k * (s2.x() + s2.y()))
      .asDiagonal();
}

// Paper 3.1 (rock size): half the largest axis.
double Rock::bounding_radius() const { return semi_axes(*this).maxCoeff(); }

// Paper 3.3, "Fast Bounce mode", step 1: the bottom of the world-aligned bounding box lies at
// the shape's support distance along -z. With r = (R_z0 s_0, R_z1 s_1, R_z2 s_2), R the rotation
// matrix's bottom row: sphere s_0; ellipsoid |r|_2; superellipsoid of exponent p, |r|_q with
// 1/p + 1/q = 1 (the dual norm; q = 8/7 for the box).
double Rock::half_height(const Eigen::Quaterniond& orientation) const {
  const Eigen::Vector3d s = semi_axes(*this);
  if (shape == BlockShape::sphere) return s.x();
  const Eigen::Vector3d r = orientation.toRotationMatrix().row(2).transpose().cwiseProduct(s);
  if (shape == BlockShape::ellipsoid) return r.norm();
  const double q = kBoxExponent / (kBoxExponent - 1.0);
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) sum += std::pow(std::abs(r[i]), q);
  return std::pow(sum, 1.0 / q);
}

// Paper 3.2: pi r_eq^2 with r_eq the radius of the sphere of the same volume.
double Rock::frontal_area() const {
  const double r_eq = std::cbrt(3.0 * volume() / (4.0 * std::numbers::pi));
  return std::numbers::pi * r_eq * r_eq;
}

}  // namespace talus
