// Mass, centre of mass and inertia tensor of a rock of uniform density (paper 3.1), integrated
// over its implicit function on a regular grid with sub-cell accuracy at the surface.
#include "talus/rockfall/implicit_shape.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace talus {

// Paper 3.1 ("each rock is provided with a mass and an inertia tensor"). The grid spans the
// rock's local-axis bounding box (world_bounds at the identity) with resolution^3 cells of sizes
// h. A cell at the surface takes the signed distance d = f / |grad f| from its centre to the
// surface and counts the inside fraction phi = clamp(1/2 - d / w, 0, 1), w = sum |n_i| h_i the
// cell's width along the normal n: the fraction of the cell's slab on the inner side of the
// tangent plane, exact when the plane passes through the centre and unbiased over the cut
// positions, which makes the volume second-order accurate. The inside part's centroid sits at
// centre - n w (1 - phi) / 2 (the slab's), and each cell adds its own second moment
// phi V h_i^2 / 12 along its axes. Cells with |f| at least the sum over the axes of the larger
// difference of f to a neighbour (twice the first-order |grad f| w / 2) lie wholly on one
// side and skip the gradient. Moments about the local origin move to the centre of mass at the
// end: I = tr(S) 1 - S with S = integral of (x - c)(x - c)^T dm.
MassProperties integrate_mass(const ImplicitShape& shape, double density, int resolution) {
  if (resolution < 1) throw std::invalid_argument("integrate_mass: the resolution must be positive");
  const int n = resolution;
  const Eigen::AlignedBox3d box = shape.world_bounds(Eigen::Quaterniond::Identity());
  const Eigen::Vector3d cell = box.sizes() / n;
  const double cell_volume = cell.prod();
  const Eigen::Vector3d cell_spread = cell.cwiseProduct(cell) / 12.0;
  // Cell centres along each axis (m).
  std::vector<Eigen::Vector3d> centres(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) centres[static_cast<std::size_t>(i)] = box.min() + (i + 0.5) * cell;
  const auto centre_of = [&](int i, int j, int k) {
    return Eigen::Vector3d(centres[static_cast<std::size_t>(i)].x(), centres[static_cast<std::size_t>(j)].y(),
                           centres[static_cast<std::size_t>(k)].z());
  };
  const std::size_t row = static_cast<std::size_t>(n);
  const std::size_t slab = row * row;
  std::vector<double> values(slab * row);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) values[(i * row + j) * row + k] = shape.value(centre_of(i, j, k));
    }
  }
  // Larger |difference| of f between the cell at `at` and its two neighbours along an axis of
  // index stride `stride`, the cell's coordinate on that axis being `coordinate` (infinite with no
  // neighbour, so that a single cell always takes the gradient).
  const auto variation = [&](std::size_t at, std::size_t stride, int coordinate) {
    double largest = n > 1 ? 0.0 : std::numeric_limits<double>::infinity();
    if (coordinate > 0) largest = std::max(largest, std::abs(values[at - stride] - values[at]));
    if (coordinate < n - 1) largest = std::max(largest, std::abs(values[at + stride] - values[at]));
    return largest;
  };
  double volume = 0.0;                                 // m3
  Eigen::Vector3d first = Eigen::Vector3d::Zero();     // integral of x_i dV (m4)
  Eigen::Vector3d squares = Eigen::Vector3d::Zero();   // integral of x_i^2 dV (m5)
  Eigen::Vector3d products = Eigen::Vector3d::Zero();  // integral of y z, x z, x y dV (m5)
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) {
        const std::size_t at = (i * row + j) * row + k;
        const double f = values[at];
        const double band = variation(at, slab, i) + variation(at, row, j) + variation(at, 1, k);
        if (f >= band) continue;  // wholly outside
        Eigen::Vector3d centre = centre_of(i, j, k);
        double fraction = 1.0;
        if (f > -band) {
          const Eigen::Vector3d g = shape.gradient(centre);
          const double g_norm = g.norm();
          if (g_norm > 0.0) {
            const Eigen::Vector3d normal = g / g_norm;
            const double width = normal.cwiseAbs().dot(cell);
            fraction = std::clamp(0.5 - f / g_norm / width, 0.0, 1.0);
            centre -= normal * (0.5 * width * (1.0 - fraction));
          }
        }
        volume += fraction;
        first += fraction * centre;
        squares += fraction * centre.cwiseProduct(centre);
        products += fraction * Eigen::Vector3d(centre.y() * centre.z(), centre.x() * centre.z(), centre.x() * centre.y());
      }
    }
  }
  volume *= cell_volume;
  first *= cell_volume;
  squares = cell_volume * squares + volume * cell_spread;
  products *= cell_volume;
  Eigen::Matrix3d second = squares.asDiagonal();
  second(1, 2) = second(2, 1) = products.x();
  second(0, 2) = second(2, 0) = products.y();
  second(0, 1) = second(1, 0) = products.z();
  MassProperties result;
  result.volume = volume;
  result.mass = density * volume;
  if (volume <= 0.0) return result;
  result.centre = first / volume;
  const Eigen::Matrix3d spread = density * (second - volume * result.centre * result.centre.transpose());
  result.inertia = spread.trace() * Eigen::Matrix3d::Identity() - spread;
  return result;
}

}  // namespace talus
