// A rock's surface as an implicit function with sample points in its local frame (paper 3.1):
// sphere, ellipsoid, or the superellipsoid of exponent kBoxExponent standing for a box
// (rock.hpp), optionally cut by planes (the parts of a pre-fractured block, paper fig. 4) and
// shifted so that the local origin is wherever the caller wants it (a part's centre of mass).
// value() is a normalised "radial" function: for the uncut shapes
//   f(p) = (|x/a|^e + |y/b|^e + |z/c|^e)^(1/e) - 1   (e = 2 ellipsoid and sphere, kBoxExponent box),
// negative inside, zero on the surface, positive outside, and about (distance / semi-axis) near
// the surface, so bisection on it converges evenly in every direction. A cut by a plane
// n.p <= d (n unit, local frame) takes max(f, (n.p - d) / r), r the shape's bounding radius.
#pragma once

#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "talus/rockfall/rock.hpp"

namespace talus {

// One sample of the rock's surface (local frame).
struct SurfaceSample {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // unit outward normal
  double area = 0;                                     // m2 of surface this sample stands for
};

// A half-space n.p <= offset in the local frame of the shape being cut (later shifts move it with
// the shape). A non-unit normal is normalised together with its offset (the same half-space).
struct CutPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();   // unit, pointing out of the kept part
  double offset = 0;                                   // m
};

class ImplicitShape {
 public:
  // The rock's shape and axes (density is not used here). samples: this many surface samples
  // (a Fibonacci set of directions, each ray-marched to the surface). Throws
  // std::invalid_argument for samples < 1 or axes that are not positive.
  explicit ImplicitShape(const Rock& rock, int samples = 256);

  // The same shape cut by a plane (the kept side is n.p <= offset), sampled again: the rays start
  // from an interior point of the kept part (the centroid of a coarse grid of its inside points),
  // so the local origin need not lie inside it. Throws std::invalid_argument when the cut leaves
  // no volume.
  ImplicitShape cut(const CutPlane& plane) const;
  // The same shape with its local origin moved to `origin` (old local frame): value(p) of the
  // result equals value(p + origin) of this one.
  ImplicitShape shifted(const Eigen::Vector3d& origin) const;

  double value(const Eigen::Vector3d& local) const;              // f (-): < 0 inside
  Eigen::Vector3d gradient(const Eigen::Vector3d& local) const;  // grad f (1/m), outward
  bool inside(const Eigen::Vector3d& local) const { return value(local) < 0.0; }

  // Largest distance (m) from the local origin to the surface: every point of the rock lies
  // within this radius. Exact for the uncut shape about its centre; for shifted or cut shapes a
  // guaranteed upper bound (a few percent above the truth, never above |shift| + uncut radius).
  double bounding_radius() const { return bounding_radius_; }
  // Half sizes (m) of the world-axis-aligned box around the rock at this orientation, and that
  // box's centre relative to the local origin (m, world axes). Exact for uncut shapes (support
  // function); for cut ones a guaranteed enclosure, within a few percent of the bounding radius
  // of the exact box (the support function bounded by duality and interpolated, see the .cpp).
  Eigen::AlignedBox3d world_bounds(const Eigen::Quaterniond& orientation) const;

  const std::vector<SurfaceSample>& surface() const { return surface_; }
  double surface_area() const;  // m2: sum of the samples' areas

 private:
  Rock rock_;
  Eigen::Vector3d semi_axes_;
  double exponent_;
  std::vector<CutPlane> cuts_;
  Eigen::Vector3d origin_ = Eigen::Vector3d::Zero();
  int sample_count_;
  double base_radius_;      // m: largest distance from the uncut shape's centre to its surface
  double bounding_radius_;  // m: bounding_radius(), updated by every constructor, cut and shift
  // Upper bounds (m) of the support function of the (cut) shape about the uncut centre at the
  // nodes of a cube map of directions (see the .cpp); a cut's bounds are interpolated from it.
  std::vector<double> support_table_;
  std::vector<SurfaceSample> surface_;
  void sample_surface();
  void tabulate_support();
  double support_bound(const Eigen::Vector3d& direction) const;  // m, direction in the uncut frame
  void update_bounding_radius();
};

// Mass properties of a solid of uniform density (paper 3.1: "each rock is provided with a mass
// and an inertia tensor"), integrated numerically over the implicit function.
struct MassProperties {
  double volume = 0;                                   // m3
  double mass = 0;                                     // kg
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();    // centre of mass, local frame (m)
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();   // kg m2 about the centre of mass, local axes
};
// Integrates on a grid of `resolution`^3 cells over the bounding cube, with sub-cell accuracy
// at the surface (documented in the .cpp); 0.5% or better on the tensor at resolution 64.
MassProperties integrate_mass(const ImplicitShape& shape, double density, int resolution = 64);

// Air friction of paper 3.2 as its surface integral over the samples:
// F = -1/2 rho Cx sum over samples facing the flow (n.v > 0, world frame) of |v| (v.n) dA  v/|v|,
// i.e. 1/2 rho Cx |v| v times the frontal area seen by the flow; for a sphere this is the closed
// form of air_drag.hpp. Returns the force (N, world frame) and, in `torque`, its moment about
// the local origin (N m, world frame).
Eigen::Vector3d surface_drag(const ImplicitShape& shape, const Eigen::Quaterniond& orientation,
                             const Eigen::Vector3d& velocity, double air_density, double drag_coefficient,
                             Eigen::Vector3d* torque = nullptr);

}  // namespace talus
