// A rock's surface as an implicit function with sample points in its local frame (paper 3.1):
// the normalised radial function of a sphere, ellipsoid or box superellipsoid, cut by planes
// (pre-fractured parts, paper fig. 4), its analytic gradient, its Fibonacci-ray surface samples
// and its bounds. Internally every point is taken to the "base" frame of the uncut shape (origin
// at its centre) by adding origin_; cut planes are stored in that frame.
#include "talus/rockfall/implicit_shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace talus {
namespace {

constexpr int kCoarseGridStart = 16;       // cells per axis of the first grid searched for an interior point
constexpr int kCoarseGridLimit = 128;      // finest such grid before a cut part counts as empty
constexpr double kRayTolerance = 1e-12;    // relative accuracy of a ray's hit distance (-)
constexpr double kBracketFactor = 1.01;    // a ray's outer end, beyond the farthest possible hit (-)
constexpr int kCubeCells = 8;              // cells per edge of each cube-map face (support table)
constexpr int kCubeNodes = kCubeCells + 1;
constexpr int kRadiusSubcells = 4;        // squares per cell edge when bounding the radius
constexpr double kMultiplierTolerance = 1e-7;  // relative accuracy of a dual multiplier (-)
constexpr int kMaxSweeps = 30;             // coordinate-descent sweeps over the cuts' multipliers
constexpr int kMaxDoublings = 60;          // bracket growth steps for one multiplier

// Semi-axes (m): the sphere's radius three times, else half the full axes (rock.hpp).
Eigen::Vector3d semi_axes_of(const Rock& rock) {
  if (rock.shape == BlockShape::sphere) return Eigen::Vector3d::Constant(0.5 * rock.axes.x());
  return 0.5 * rock.axes;
}

// Largest distance (m) from the centre to the surface of sum |x_i / s_i|^e = 1. For e = 2 the
// largest semi-axis; for e > 2, Lagrange's condition gives x_i proportional to s_i^(e/(e-2)),
// whence the distance (sum s_i^(2e/(e-2)))^((1 - 2/e)/2) (3^(3/8) s for a cube of exponent 8).
double farthest_surface_distance(const Eigen::Vector3d& s, double e) {
  if (e == 2.0) return s.maxCoeff();
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) sum += std::pow(s[i], 2.0 * e / (e - 2.0));
  return std::pow(sum, 0.5 * (1.0 - 2.0 / e));
}

// Paper 3.1, the uncut implicit function (implicit_shape.hpp): (sum |x_i/s_i|^e)^(1/e) - 1 at a
// base-frame point p (m); e = 2 by a square root, e = 8 by repeated squaring and three roots.
static_assert(kBoxExponent == 8.0, "radial_value and radial_gradient square their way to the 8th power");
double radial_value(const Eigen::Vector3d& p, const Eigen::Vector3d& s, double e) {
  const Eigen::Vector3d t = p.cwiseQuotient(s);
  if (e == 2.0) return std::sqrt(t.squaredNorm()) - 1.0;
  const Eigen::Vector3d t2 = t.cwiseProduct(t);
  const Eigen::Vector3d t4 = t2.cwiseProduct(t2);
  return std::sqrt(std::sqrt(std::sqrt(t4.squaredNorm()))) - 1.0;
}

// Gradient (1/m) of radial_value: t_i / (s_i F) for e = 2 and t_i^7 / (s_i F^7) = t_i^7 F /
// (s_i S) for e = 8, with t = p / s, S = sum t_i^e and F = S^(1/e); zero at the centre.
Eigen::Vector3d radial_gradient(const Eigen::Vector3d& p, const Eigen::Vector3d& s, double e) {
  const Eigen::Vector3d t = p.cwiseQuotient(s);
  if (e == 2.0) {
    const double f = t.norm();
    if (f == 0.0) return Eigen::Vector3d::Zero();
    return t.cwiseQuotient(s) / f;
  }
  const Eigen::Vector3d t2 = t.cwiseProduct(t);
  const Eigen::Vector3d t4 = t2.cwiseProduct(t2);
  const double sum = t4.squaredNorm();
  if (sum == 0.0) return Eigen::Vector3d::Zero();
  const double f = std::sqrt(std::sqrt(std::sqrt(sum)));
  const Eigen::Vector3d t7 = t4.cwiseProduct(t2).cwiseProduct(t);
  return t7.cwiseQuotient(s) * (f / sum);
}

// Support function max over the shape of u.p (m per unit of u) of the uncut shape centred at
// the origin, along a direction u of any length (it is positively homogeneous): the dual norm of
// (u_i s_i), |.|_2 for e = 2 and |.|_q with 1/e + 1/q = 1 otherwise (as Rock::half_height does
// for the vertical).
double radial_support(const Eigen::Vector3d& u, const Eigen::Vector3d& s, double e) {
  const Eigen::Vector3d r = u.cwiseProduct(s);
  if (e == 2.0) return r.norm();
  const double q = e / (e - 1.0);
  double sum = 0.0;
  for (int i = 0; i < 3; ++i) sum += std::pow(std::abs(r[i]), q);
  return std::pow(sum, 1.0 / q);
}

// Support point (m) of the uncut centred shape along a direction v (any length): the gradient of
// radial_support in v, S^2 v / |S v| for e = 2 and s_i sign(r_i) (|r_i| / |r|_q)^(q-1) with
// r = s v otherwise; zero for v = 0.
Eigen::Vector3d radial_support_point(const Eigen::Vector3d& v, const Eigen::Vector3d& s, double e) {
  const Eigen::Vector3d r = v.cwiseProduct(s);
  if (e == 2.0) {
    const double h = r.norm();
    if (h == 0.0) return Eigen::Vector3d::Zero();
    return s.cwiseProduct(r) / h;
  }
  const double q = e / (e - 1.0);
  const double h = radial_support(v, s, e);
  if (h == 0.0) return Eigen::Vector3d::Zero();
  Eigen::Vector3d p;
  for (int i = 0; i < 3; ++i) p[i] = s[i] * std::copysign(std::pow(std::abs(r[i]) / h, q - 1.0), r[i]);
  return p;
}

// Upper bound (m) of the support function along c of the uncut centred shape B cut by the
// half-spaces n_k.p <= d_k (paper fig. 4), by weak duality: for every lambda >= 0,
//   max over the part of c.p <= h_B(c - sum lambda_k n_k) + sum lambda_k d_k,
// since c.p = (c - sum lambda_k n_k).p + sum lambda_k n_k.p. The right side is convex in lambda;
// coordinate descent minimises it (each multiplier solves d_k = n_k . p*(c - sum lambda n), p*
// the support point, by bisection), warm-started from `multipliers`, which it updates. Any
// multipliers give a valid bound, so an early stop only loosens it.
double cut_support_bound(const Eigen::Vector3d& c, const Eigen::Vector3d& s, double e,
                         const std::vector<CutPlane>& cuts, std::vector<double>& multipliers) {
  const double scale = std::max(c.norm(), 1.0);
  for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
    double change = 0.0;
    for (std::size_t k = 0; k < cuts.size(); ++k) {
      Eigen::Vector3d rest = c;
      for (std::size_t j = 0; j < cuts.size(); ++j) {
        if (j != k) rest -= multipliers[j] * cuts[j].normal;
      }
      const CutPlane& plane = cuts[k];
      const auto slope = [&](double lambda) {
        return plane.offset - plane.normal.dot(radial_support_point(rest - lambda * plane.normal, s, e));
      };
      double lambda = 0.0;
      if (slope(0.0) < 0.0) {
        double low = 0.0;
        double high = multipliers[k] > 0.0 ? 2.0 * multipliers[k] : scale;
        for (int i = 0; i < kMaxDoublings && slope(high) < 0.0; ++i) {
          low = high;
          high *= 2.0;
        }
        while (high - low > kMultiplierTolerance * high) {
          const double middle = 0.5 * (low + high);
          if (slope(middle) < 0.0) {
            low = middle;
          } else {
            high = middle;
          }
        }
        lambda = 0.5 * (low + high);
      }
      change = std::max(change, std::abs(lambda - multipliers[k]));
      multipliers[k] = lambda;
    }
    if (change <= kMultiplierTolerance * scale) break;
  }
  Eigen::Vector3d v = c;
  double bound = 0.0;
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    v -= multipliers[k] * cuts[k].normal;
    bound += multipliers[k] * cuts[k].offset;
  }
  return bound + radial_support(v, s, e);
}

// Cube map of directions: face f lies on axis f / 2 (side + for even f), at face coordinates
// u = -1 + 2 x / kCubeCells along the next axis and w = -1 + 2 y / kCubeCells along the one
// after; its nodes sit at integer (x, y), stored at cube_index.
std::size_t cube_index(int face, int i, int j) {
  return static_cast<std::size_t>((face * kCubeNodes + i) * kCubeNodes + j);
}
// Face point at continuous cube-map coordinates (x, y) in cells (0 to kCubeCells).
Eigen::Vector3d cube_point(int face, double x, double y) {
  const int axis = face / 2;
  Eigen::Vector3d c;
  c[axis] = face % 2 == 0 ? 1.0 : -1.0;
  c[(axis + 1) % 3] = -1.0 + 2.0 * x / kCubeCells;
  c[(axis + 2) % 3] = -1.0 + 2.0 * y / kCubeCells;
  return c;
}
// Linear interpolation of the table on face `face` at (x, y) over the cell's triangle below or
// above its anti-diagonal fx + fy = 1.
double interpolate_face(const std::vector<double>& table, int face, double x, double y) {
  const int i = std::clamp(static_cast<int>(x), 0, kCubeCells - 1);
  const int j = std::clamp(static_cast<int>(y), 0, kCubeCells - 1);
  const double fx = x - i;
  const double fy = y - j;
  const double h00 = table[cube_index(face, i, j)];
  const double h10 = table[cube_index(face, i + 1, j)];
  const double h01 = table[cube_index(face, i, j + 1)];
  const double h11 = table[cube_index(face, i + 1, j + 1)];
  if (fx + fy <= 1.0) return h00 + fx * (h10 - h00) + fy * (h01 - h00);
  return h11 + (1.0 - fx) * (h01 - h11) + (1.0 - fy) * (h10 - h11);
}

// Direction k of a Fibonacci sphere of n: heights at the midpoints of n equal bands (equal
// areas), longitudes advancing by the golden angle.
Eigen::Vector3d fibonacci_direction(int k, int n) {
  const double golden_angle = std::numbers::pi * (3.0 - std::sqrt(5.0));
  const double z = 1.0 - (2.0 * k + 1.0) / n;
  const double rho = std::sqrt(std::max(0.0, 1.0 - z * z));
  const double longitude = golden_angle * k;
  return {rho * std::cos(longitude), rho * std::sin(longitude), z};
}

}  // namespace

// Paper 3.1: the rock's implicit surface in its local frame, centred, sampled.
ImplicitShape::ImplicitShape(const Rock& rock, int samples)
    : rock_(rock),
      semi_axes_(semi_axes_of(rock)),
      exponent_(rock.shape == BlockShape::box ? kBoxExponent : 2.0),
      sample_count_(samples),
      base_radius_(0.0),
      bounding_radius_(0.0) {
  if (samples < 1) throw std::invalid_argument("ImplicitShape: the sample count must be positive");
  if (!(semi_axes_.minCoeff() > 0.0)) throw std::invalid_argument("ImplicitShape: the rock's axes must be positive");
  base_radius_ = farthest_surface_distance(semi_axes_, exponent_);
  sample_surface();
  tabulate_support();
  update_bounding_radius();
}

// Paper fig. 4: a part of a pre-fractured block, the shape intersected with n.p <= offset.
ImplicitShape ImplicitShape::cut(const CutPlane& plane) const {
  const double length = plane.normal.norm();
  if (!(length > 0.0)) throw std::invalid_argument("ImplicitShape::cut: the plane's normal must be non-zero");
  ImplicitShape part = *this;
  CutPlane base;
  base.normal = plane.normal / length;
  base.offset = plane.offset / length + base.normal.dot(origin_);
  part.cuts_.push_back(base);
  part.sample_surface();
  part.tabulate_support();
  part.update_bounding_radius();
  return part;
}

// Moves the local origin (paper 3.1: the rigid body's frame sits at its centre of mass).
ImplicitShape ImplicitShape::shifted(const Eigen::Vector3d& origin) const {
  ImplicitShape moved = *this;
  moved.origin_ += origin;
  for (SurfaceSample& sample : moved.surface_) sample.position -= origin;
  moved.update_bounding_radius();
  return moved;
}

// Paper 3.1 (implicit surface): max of the radial function and of each cut's (n.p - d) / r.
double ImplicitShape::value(const Eigen::Vector3d& local) const {
  const Eigen::Vector3d p = local + origin_;
  double f = radial_value(p, semi_axes_, exponent_);
  for (const CutPlane& plane : cuts_) f = std::max(f, (plane.normal.dot(p) - plane.offset) / base_radius_);
  return f;
}

// Gradient (1/m) of value(): that of the piece the max selects.
Eigen::Vector3d ImplicitShape::gradient(const Eigen::Vector3d& local) const {
  const Eigen::Vector3d p = local + origin_;
  double f = radial_value(p, semi_axes_, exponent_);
  const CutPlane* active = nullptr;
  for (const CutPlane& plane : cuts_) {
    const double g = (plane.normal.dot(p) - plane.offset) / base_radius_;
    if (g > f) {
      f = g;
      active = &plane;
    }
  }
  if (active != nullptr) return active->normal / base_radius_;
  return radial_gradient(p, semi_axes_, exponent_);
}

// Axis-aligned bounds of the rock at an orientation (paper 3.3 sizes the piston carpet with
// them): along world axis j, with u = R^T e_j (row j of the rotation) and o = origin_, the rock
// spans [-h(-u) - u.o, h(u) - u.o], h the support function about the uncut centre: exact for
// uncut shapes, support_bound() (an upper bound, also capped by the uncut h) for cut ones.
Eigen::AlignedBox3d ImplicitShape::world_bounds(const Eigen::Quaterniond& orientation) const {
  const Eigen::Matrix3d rotation = orientation.normalized().toRotationMatrix();
  Eigen::AlignedBox3d box;
  for (int j = 0; j < 3; ++j) {
    const Eigen::Vector3d u = rotation.row(j).transpose();
    const double uncut = radial_support(u, semi_axes_, exponent_);
    double upper = uncut;
    double lower = uncut;
    if (!cuts_.empty()) {
      upper = std::min(upper, support_bound(u));
      lower = std::min(lower, support_bound(-u));
    }
    const double shift = u.dot(origin_);
    box.min()[j] = -lower - shift;
    box.max()[j] = upper - shift;
  }
  return box;
}

// Paper 3.1 (surface area): the sum of the samples' areas (m2).
double ImplicitShape::surface_area() const {
  double area = 0.0;
  for (const SurfaceSample& sample : surface_) area += sample.area;
  return area;
}

// Paper 3.1 (sample points): N rays from an interior point c along a Fibonacci sphere of
// directions, each bisected to f = 0; the sample at distance r stands for the area
// r^2 dOmega / (n . r_hat) that its solid angle dOmega = 4 pi / N cuts from the surface (every
// ray meets the surface once: convex parts are star-shaped about any interior point). c is the
// uncut shape's centre, or for cut shapes the centroid of a coarse grid's interior cell
// centres (inside, by convexity), so the local origin of a cut part need not be inside it.
// Accuracy at 256 samples: the sphere's area exactly, the ellipsoid's to 1e-6, the box's to
// 0.3% (its rounded edges), cut parts to 1% to 2% (the area element jumps at the cut's rim).
void ImplicitShape::sample_surface() {
  Eigen::Vector3d centre = -origin_;
  if (!cuts_.empty()) {
    const Eigen::Vector3d extent = semi_axes_;  // the uncut shape's bounding box half sizes in base axes
    bool found = false;
    for (int n = kCoarseGridStart; n <= kCoarseGridLimit && !found; n *= 2) {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      long count = 0;
      for (int i = 0; i < n; ++i) {
        for (int j = 0; j < n; ++j) {
          for (int k = 0; k < n; ++k) {
            const Eigen::Vector3d cell = (Eigen::Vector3d(i, j, k).array() + 0.5) / n * 2.0 - 1.0;
            const Eigen::Vector3d local = cell.cwiseProduct(extent) - origin_;
            if (value(local) < 0.0) {
              sum += local;
              ++count;
            }
          }
        }
      }
      if (count > 0) {
        centre = sum / static_cast<double>(count);
        found = true;
      }
    }
    if (!found) throw std::invalid_argument("ImplicitShape::cut: the cut leaves no volume");
  }
  const double solid_angle = 4.0 * std::numbers::pi / sample_count_;
  const double reach = kBracketFactor * ((centre + origin_).norm() + base_radius_);
  surface_.assign(static_cast<std::size_t>(sample_count_), SurfaceSample{});
  for (int k = 0; k < sample_count_; ++k) {
    const Eigen::Vector3d direction = fibonacci_direction(k, sample_count_);
    double inner = 0.0;
    double outer = reach;
    while (outer - inner > kRayTolerance * outer) {
      const double middle = 0.5 * (inner + outer);
      if (value(centre + middle * direction) < 0.0) {
        inner = middle;
      } else {
        outer = middle;
      }
    }
    const double distance = 0.5 * (inner + outer);
    SurfaceSample& sample = surface_[static_cast<std::size_t>(k)];
    sample.position = centre + distance * direction;
    sample.normal = gradient(sample.position).normalized();
    sample.area = distance * distance * solid_angle / sample.normal.dot(direction);
  }
}

// Support table (paper fig. 4 parts; see cut_support_bound): upper bounds of the support
// function about the uncut centre, at every node of a cube map of kCubeCells x kCubeCells cells
// per face, the nodes visited in order so that each warm-starts the next one's multipliers.
void ImplicitShape::tabulate_support() {
  support_table_.assign(static_cast<std::size_t>(6 * kCubeNodes * kCubeNodes), 0.0);
  std::vector<double> multipliers(cuts_.size(), 0.0);
  for (int face = 0; face < 6; ++face) {
    for (int i = 0; i < kCubeNodes; ++i) {
      for (int j = 0; j < kCubeNodes; ++j) {
        support_table_[cube_index(face, i, j)] =
            cut_support_bound(cube_point(face, i, j), semi_axes_, exponent_, cuts_, multipliers);
      }
    }
  }
}

// Upper bound (m) of the support function along a direction (uncut frame, any length): the
// direction meets the cube face of its largest component |v_a| at v / |v_a|, inside one of the
// two triangles of a cell; the support function is convex and positively homogeneous, so
// |v_a| times the linear interpolation of the triangle's node values bounds it from above.
double ImplicitShape::support_bound(const Eigen::Vector3d& direction) const {
  int axis = 0;
  direction.cwiseAbs().maxCoeff(&axis);
  const double scale = std::abs(direction[axis]);
  if (scale == 0.0) return 0.0;
  const int face = 2 * axis + (direction[axis] > 0.0 ? 0 : 1);
  const double x = 0.5 * (direction[(axis + 1) % 3] / scale + 1.0) * kCubeCells;
  const double y = 0.5 * (direction[(axis + 2) % 3] / scale + 1.0) * kCubeCells;
  return scale * interpolate_face(support_table_, face, x, y);
}

// Paper 3.1 (bounding sphere about the local origin): exact for the centred uncut shape. Else
// the largest distance is the largest support about the origin, h(v) / |v| - v.o / |v|. Each
// cube-map cell is split into kRadiusSubcells^2 squares whose corners lie on the triangles'
// edges; on a square the interpolated bound of h(v) - v.o is at most its largest corner value
// (linear on each piece) and |v| at least its value at the square's point nearest the face
// centre, which bounds the ratio. Capped by |o| + the uncut radius (the shape lies inside its
// uncut self).
void ImplicitShape::update_bounding_radius() {
  if (cuts_.empty() && origin_.isZero(0.0)) {
    bounding_radius_ = base_radius_;
    return;
  }
  constexpr int n = kCubeCells * kRadiusSubcells;
  constexpr double step = 1.0 / kRadiusSubcells;  // cells
  const auto nearest_to_centre = [](int a) {
    const double low = -1.0 + 2.0 * a / n;
    const double high = -1.0 + 2.0 * (a + 1) / n;
    return low <= 0.0 && high >= 0.0 ? 0.0 : std::min(std::abs(low), std::abs(high));
  };
  std::vector<double> excess(static_cast<std::size_t>((n + 1) * (n + 1)));
  double farthest = 0.0;
  for (int face = 0; face < 6; ++face) {
    for (int a = 0; a <= n; ++a) {
      for (int b = 0; b <= n; ++b) {
        const double x = a * step;
        const double y = b * step;
        excess[static_cast<std::size_t>(a * (n + 1) + b)] =
            interpolate_face(support_table_, face, x, y) - cube_point(face, x, y).dot(origin_);
      }
    }
    for (int a = 0; a < n; ++a) {
      for (int b = 0; b < n; ++b) {
        const auto at = [&](int da, int db) { return excess[static_cast<std::size_t>((a + da) * (n + 1) + b + db)]; };
        const double largest = std::max({at(0, 0), at(1, 0), at(0, 1), at(1, 1)});
        const double u = nearest_to_centre(a);
        const double w = nearest_to_centre(b);
        farthest = std::max(farthest, largest / std::sqrt(1.0 + u * u + w * w));
      }
    }
  }
  bounding_radius_ = std::min(origin_.norm() + base_radius_, farthest);
}

}  // namespace talus
