// Contact of the mud columns with the bilinear ground (paper 2.2 and 4.1, docs/architecture.md section 2
// "contact ... against the ground model"; docs/mudflow.md "Ground contact"): every particle's foot
// stays on the surface, its velocity in the surface's tangent plane, and a particle that leaves
// the ground model's valid area is reported so the caller can count it as outflow.
#pragma once

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "talus/ground/ground_model.hpp"
#include "talus/mudflow/particle_set.hpp"

namespace talus {

// The unit upward normal of the ground at each particle's foot, kept as structure of arrays;
// z is cos(theta), theta the local slope angle.
struct FootNormals {
  std::vector<double> x, y, z;

  void resize(std::size_t count) {
    x.resize(count);
    y.resize(count);
    z.resize(count, 1.0);
  }
  Eigen::Vector3d at(std::size_t i) const { return {x[i], y[i], z[i]}; }
};

// The slope at every node of the ground for `[contact] node_normals` (AvaFrame com1DFA's
// normals, DFAnumerics "Cell normals"; docs/mudflow.md section 6): the mean of the gradients at
// the centres of the node's four squares, computed once for a run.
class NodeSlopes {
 public:
  explicit NodeSlopes(const GroundModel& ground);
  // The nodes' slopes interpolated bilinearly at a point of `square` (dz/dx, dz/dy); false where
  // one of its nodes has none (a node of that node's 3 x 3 block is invalid).
  bool interpolated(const NodeSquare& square, Eigen::Vector2d& slope) const;

 private:
  std::vector<Eigen::Vector2d> slope_;  // per node, row-major as the ground's grid
  std::vector<char> has_slope_;
};

// Unit upward normal of the ground at a point of a node square. Without `node_slopes` the
// bilinear surface's own, which turns at every node line; with them the normal of the nodes'
// slopes interpolated there, which turns smoothly over about two cells, and the square's own
// where they have none.
Eigen::Vector3d ground_normal(const GroundModel& ground, const NodeSquare& square,
                              const NodeSlopes* node_slopes = nullptr);

// The unit normal averaged over a step (AvaFrame com1DFA's gravity normal): the mean of the foot's
// normal `foot` and the ground's normal at (x, y) + velocity x step, normalised; `foot` where that
// place is off the ground model's valid area.
Eigen::Vector3d step_averaged_normal(const GroundModel& ground, const Eigen::Vector3d& foot, double x, double y,
                                     const Eigen::Vector3d& velocity, double step,
                                     const NodeSlopes* node_slopes = nullptr);

// The part of v in the plane of unit normal n.
inline Eigen::Vector3d tangent_part(const Eigen::Vector3d& v, const Eigen::Vector3d& n) { return v - v.dot(n) * n; }

// v turned into the plane of unit normal n with its length kept: a particle that follows a
// curved surface keeps its kinetic energy (the ground's normal reaction does no work).
Eigen::Vector3d turned_into_plane(const Eigen::Vector3d& v, const Eigen::Vector3d& n);

// Puts particle i's foot on the ground under (x, y): z from the surface, the normal stored in
// `normals`, the velocity turned into the tangent plane. (x, y) must lie in the valid area.
void place_on_ground(const GroundModel& ground, ParticleSet& particles, std::size_t i, FootNormals& normals,
                     const NodeSlopes* node_slopes = nullptr);

// Moves particle i for `duration` (s) with its horizontal velocity, then places it on the ground
// there. Returns false, and leaves the particle where it was, when the new place is outside the
// ground model's valid area (or not a number).
bool drift_on_ground(const GroundModel& ground, ParticleSet& particles, std::size_t i, double duration,
                     FootNormals& normals, const NodeSlopes* node_slopes = nullptr);

// Curvature kappa (1/m) of the ground along the unit tangent `direction` at (x, y), positive in
// hollows: minus the change of the unit normal along the direction per metre of path, from the
// normals `half_span` (m, horizontal) ahead and behind (one side only where the other leaves the
// valid area). Bilinear surfaces bend at node lines, so half_span of about half a cell averages
// a bend over one cell.
double curvature_along(const GroundModel& ground, double x, double y, const Eigen::Vector3d& direction,
                       double half_span, const NodeSlopes* node_slopes = nullptr);

// cos(theta) of the ground at the centre of valid DEM cell (col, row), from the slope's central
// differences there (one-sided where only one neighbour along an axis is valid, 0 where none is).
double cell_cos_slope(const GroundModel& ground, int col, int row);

}  // namespace talus
