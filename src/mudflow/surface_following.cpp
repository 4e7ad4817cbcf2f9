// Keeping the mud columns on the bilinear ground (paper 2.2, 4.1; docs/mudflow.md "Ground contact").
#include "talus/mudflow/surface_following.hpp"

#include <cmath>

namespace talus {
namespace {

// Slope (dz/dx, dz/dy) at node (col, row) from its valid neighbours: central differences where
// both neighbours along an axis are valid, one-sided where only one is, 0 where none is.
Eigen::Vector2d slope_from_neighbours(const Grid<double>& z, int col, int row) {
  const GridSpec& spec = z.spec();
  auto difference = [&](int dc, int dr, double step) {
    const bool ahead = z.is_valid(col + dc, row + dr);
    const bool behind = z.is_valid(col - dc, row - dr);
    const double here = z.at(col, row);
    if (ahead && behind) return (z.at(col + dc, row + dr) - z.at(col - dc, row - dr)) / (2.0 * step);
    if (ahead) return (z.at(col + dc, row + dr) - here) / step;
    if (behind) return (here - z.at(col - dc, row - dr)) / step;
    return 0.0;
  };
  return {difference(1, 0, spec.geotransform[1]), difference(0, 1, spec.geotransform[5])};
}

// The slope at node (col, row) as the mean of the gradients at the centres of its four squares
// (a 3 x 3 stencil: the central differences along one axis, weighted 1 2 1 across it); false
// where a node of the block is invalid.
bool slope_of_four_squares(const Grid<double>& z, int col, int row, Eigen::Vector2d& slope) {
  for (int dr = -1; dr <= 1; ++dr) {
    for (int dc = -1; dc <= 1; ++dc) {
      if (!z.is_valid(col + dc, row + dr)) return false;
    }
  }
  auto at = [&](int dc, int dr) { return z.at(col + dc, row + dr); };
  const double dx = z.spec().geotransform[1], dy = z.spec().geotransform[5];
  slope.x() = (2.0 * (at(1, 0) - at(-1, 0)) + (at(1, 1) - at(-1, 1)) + (at(1, -1) - at(-1, -1))) / (8.0 * dx);
  slope.y() = (2.0 * (at(0, 1) - at(0, -1)) + (at(1, 1) - at(1, -1)) + (at(-1, 1) - at(-1, -1))) / (8.0 * dy);
  return true;
}

}  // namespace


NodeSlopes::NodeSlopes(const GroundModel& ground) {
  const Grid<double>& z = ground.elevation_grid();
  const GridSpec& spec = z.spec();
  slope_.assign(spec.cell_count(), Eigen::Vector2d::Zero());
  has_slope_.assign(spec.cell_count(), 0);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) {
      const std::size_t node = z.index(col, row);
      has_slope_[node] = slope_of_four_squares(z, col, row, slope_[node]);
    }
  }
}

bool NodeSlopes::interpolated(const NodeSquare& square, Eigen::Vector2d& slope) const {
  const std::size_t nodes[4] = {square.i00, square.i10, square.i01, square.i11};
  const double weights[4] = {(1.0 - square.fx) * (1.0 - square.fy), square.fx * (1.0 - square.fy),
                             (1.0 - square.fx) * square.fy, square.fx * square.fy};
  slope = Eigen::Vector2d::Zero();
  for (int k = 0; k < 4; ++k) {
    if (!has_slope_[nodes[k]]) return false;
    slope += weights[k] * slope_[nodes[k]];
  }
  return true;
}

// The normal of z = f(x, y) is (-f_x, -f_y, 1) / |(-f_x, -f_y, 1)| (paper 2.2, fig. 3a).
Eigen::Vector3d ground_normal(const GroundModel& ground, const NodeSquare& square, const NodeSlopes* node_slopes) {
  Eigen::Vector2d gradient;
  if (!node_slopes || !node_slopes->interpolated(square, gradient)) gradient = ground.slope(square);
  return Eigen::Vector3d(-gradient.x(), -gradient.y(), 1.0).normalized();
}

// A midpoint rule for the ground's turn under the particle during its step: on a bend the pull
// along the ground is the one the particle meets on average, not the one it leaves.
Eigen::Vector3d step_averaged_normal(const GroundModel& ground, const Eigen::Vector3d& foot, double x, double y,
                                     const Eigen::Vector3d& velocity, double step, const NodeSlopes* node_slopes) {
  const double ahead_x = x + velocity.x() * step, ahead_y = y + velocity.y() * step;
  if (!ground.contains(ahead_x, ahead_y)) return foot;
  return (foot + ground_normal(ground, ground.locate(ahead_x, ahead_y), node_slopes)).normalized();
}

Eigen::Vector3d turned_into_plane(const Eigen::Vector3d& v, const Eigen::Vector3d& n) {
  const Eigen::Vector3d tangent = tangent_part(v, n);
  const double length = tangent.norm();
  if (!(length > 0.0)) return tangent;
  return tangent * (v.norm() / length);
}

void place_on_ground(const GroundModel& ground, ParticleSet& particles, std::size_t i, FootNormals& normals,
                     const NodeSlopes* node_slopes) {
  const NodeSquare square = ground.locate(particles.x[i], particles.y[i]);
  particles.z[i] = ground.elevation(square);
  const Eigen::Vector3d n = ground_normal(ground, square, node_slopes);
  normals.x[i] = n.x();
  normals.y[i] = n.y();
  normals.z[i] = n.z();
  const Eigen::Vector3d v = turned_into_plane(particles.velocity(i), n);
  particles.vx[i] = v.x();
  particles.vy[i] = v.y();
  particles.vz[i] = v.z();
}

// The foot moves with the horizontal part of the velocity; the vertical part is the ground's
// (the velocity is tangent, so this is the motion along the surface to first order).
bool drift_on_ground(const GroundModel& ground, ParticleSet& particles, std::size_t i, double duration,
                     FootNormals& normals, const NodeSlopes* node_slopes) {
  const double x = particles.x[i] + particles.vx[i] * duration;
  const double y = particles.y[i] + particles.vy[i] * duration;
  if (!ground.contains(x, y)) return false;
  particles.x[i] = x;
  particles.y[i] = y;
  place_on_ground(ground, particles, i, normals, node_slopes);
  return true;
}

double curvature_along(const GroundModel& ground, double x, double y, const Eigen::Vector3d& direction,
                       double half_span, const NodeSlopes* node_slopes) {
  const double horizontal = std::sqrt(direction.x() * direction.x() + direction.y() * direction.y());
  if (!(horizontal > 0.0)) return 0.0;
  const double ex = direction.x() / horizontal * half_span, ey = direction.y() / horizontal * half_span;
  double ahead_x = x + ex, ahead_y = y + ey, behind_x = x - ex, behind_y = y - ey;
  if (!ground.contains(ahead_x, ahead_y)) {
    ahead_x = x;
    ahead_y = y;
  }
  if (!ground.contains(behind_x, behind_y)) {
    behind_x = x;
    behind_y = y;
  }
  const NodeSquare ahead = ground.locate(ahead_x, ahead_y), behind = ground.locate(behind_x, behind_y);
  const Eigen::Vector3d a(ahead_x, ahead_y, ground.elevation(ahead));
  const Eigen::Vector3d b(behind_x, behind_y, ground.elevation(behind));
  const double path = (a - b).norm();
  if (!(path > 0.0)) return 0.0;
  return -(ground_normal(ground, ahead, node_slopes) - ground_normal(ground, behind, node_slopes)).dot(direction) /
         path;
}

// The slope's central differences at the node: the mean of the four bilinear squares' gradients
// there, where the surface itself has a kink (paper 2.2).
double cell_cos_slope(const GroundModel& ground, int col, int row) {
  const Eigen::Vector2d gradient = slope_from_neighbours(ground.elevation_grid(), col, row);
  return 1.0 / std::sqrt(1.0 + gradient.squaredNorm());
}

}  // namespace talus
