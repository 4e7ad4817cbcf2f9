// The rock of the full model as a rigid body (paper 3.1): "rigid solids defined by an implicit
// surface whose sample points are stored in a local frame ... provided with a mass and an
// inertia tensor, and animated with usual dynamic laws of motion". The body frame has its
// origin at the centre of mass and the rock's local axes. A body is a list of rigid parts (an
// implicit shape each, placed in the body frame, with its own mass properties): one for an
// intact rock, several for a pre-fractured block or its fragments (paper fig. 4, fracture.hpp).
// The state carries the angular momentum in the world frame; the integrator's two halves are
// kick() and drift(). Equations: docs/rockfall-full.md, section 2.
#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "talus/rockfall/implicit_shape.hpp"
#include "talus/rockfall/rock.hpp"

namespace talus {

// One rigid part: its implicit shape, whose local origin sits at `offset` in the body frame
// (body point p is the shape's local point p - offset; the axes are shared). The local origin is
// the part's centre of mass.
struct RockPart {
  ImplicitShape shape;
  Eigen::Vector3d offset = Eigen::Vector3d::Zero();  // m, body frame
  double mass = 0;                                    // kg
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // kg m2 about the part's centre, body axes
  // A part cut from a rock (paper fig. 4): the planes that bound it (local frame, normals out of
  // it) and the uncut rock's shape in the same local frame. None for an uncut rock.
  std::vector<CutPlane> cuts = {};
  std::optional<ImplicitShape> whole = std::nullopt;
};

// Centre of mass of a list of parts (m, in the frame of their offsets): sum m_p offset_p / sum m_p.
Eigen::Vector3d centre_of_mass(const std::vector<RockPart>& parts);
// The rock's smallest semi-axis (m): a sphere's radius, else half its smallest axis.
double smallest_semi_axis(const Rock& rock);

class RigidRock {
 public:
  // Paper 3.1: the rock's implicit shape (surface_samples samples) moved to its centre of mass;
  // mass and inertia integrated over it (integrate_mass at mass_resolution, Rock::density).
  RigidRock(const Rock& rock, int surface_samples, int mass_resolution);
  // Paper fig. 4: a body made of `parts` (offsets in any frame with the body's axes), moved so
  // that the body frame's origin is their centre of mass (centre_of_mass); mass and inertia are
  // the parts' sums (parallel-axis theorem). inner_radius (m): the smallest semi-axis of the rock
  // the parts were cut from. Throws std::invalid_argument for no parts or no mass.
  RigidRock(std::vector<RockPart> parts, double inner_radius);

  double mass() const { return mass_; }                                       // kg
  const Eigen::Matrix3d& inertia() const { return inertia_; }                 // kg m2, body frame, about the centre
  const Eigen::Matrix3d& inverse_inertia() const { return inverse_inertia_; } // 1/(kg m2)
  double min_inertia() const { return min_inertia_; }                         // kg m2: smallest principal moment
  double anisotropy() const { return anisotropy_; }                           // (I_max - I_min) / I_max (-)
  double bounding_radius() const { return bounding_radius_; }                 // m: the rock lies within it
  // The rock's smallest semi-axis (m). Each part's function is a gauge of a convex body that
  // holds a ball of this radius, so it changes by at most 1 / inner_radius per metre: a point
  // where value() = f > 0 lies at least f x inner_radius outside the rock.
  double inner_radius() const { return inner_radius_; }
  const std::vector<RockPart>& parts() const { return parts_; }
  // The surface samples of the parts that are not covered by another part (body frame): the
  // body's outer surface, without the faces that parts share; a whole block's are the uncut
  // rock's (RockPart::whole).
  const std::vector<SurfaceSample>& skin() const { return skin_; }

  // The body's implicit function at a body-frame point (m): the smallest over the parts (-),
  // negative inside; and the gradient (1/m, body frame) of the part that gives it. For a whole
  // pre-fractured block (parts cut from one rock, no cut face on its surface) both are the uncut
  // rock's (RockPart::whole): equal to the parts' outside the rock and on its surface, negative
  // inside it too, and cheaper by the number of parts.
  double value(const Eigen::Vector3d& body) const;
  Eigen::Vector3d gradient(const Eigen::Vector3d& body) const;
  // Index of the part whose function is the smallest at a body-frame point (m): the part that
  // holds it, or the nearest one in the units of the functions (the first on ties).
  std::size_t part_at(const Eigen::Vector3d& body) const;
  // True when a cut face of a part is on the body's surface (a fragment, paper fig. 4): a cut
  // plane of a part whose point nearest the part's centre, moved kSkinProbe x inner_radius out
  // of it, lies inside no other part.
  bool has_cut_faces() const { return !cut_faces_.empty(); }
  // For a body with cut faces, how deep a body-frame point inside it lies below its surface (m,
  // docs/rockfall-full.md, section 3.5), in the part that holds it (part_at): the smallest of its
  // distances to that part's cut faces on the body's surface and of -f x inner_radius, f the
  // uncut rock's function (a lower bound of the distance to the rock's outer surface), so it
  // falls to zero continuously wherever the point reaches the surface. `gradient` gets the
  // gradient of the smallest piece (body frame, pointing inwards: -n for a face of normal n,
  // -inner_radius grad f for the outer surface). Infinity for a body without cut faces.
  double depth_inside(const Eigen::Vector3d& body, Eigen::Vector3d& gradient) const;

  // World-axis-aligned box around the body at this orientation, relative to the centre (m).
  Eigen::AlignedBox3d world_bounds(const Eigen::Quaterniond& orientation) const;
  // Air friction of paper 3.2 over the body's skin (N, world), and its moment about the centre
  // in `torque` (N m, world).
  Eigen::Vector3d drag(const Eigen::Quaterniond& orientation, const Eigen::Vector3d& velocity, double air_density,
                       double drag_coefficient, Eigen::Vector3d& torque) const;

 private:
  std::vector<RockPart> parts_;
  std::vector<SurfaceSample> skin_;
  std::vector<std::vector<CutPlane>> cut_faces_;  // per part, its cut planes on the body's surface; empty: none anywhere
  bool whole_ = false;                            // a whole block: value and gradient from parts_[0].whole
  double mass_ = 0, min_inertia_ = 0, anisotropy_ = 0, bounding_radius_ = 0, inner_radius_ = 0;
  Eigen::Matrix3d inertia_ = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d inverse_inertia_ = Eigen::Matrix3d::Zero();
};

// The body's state (paper 3.1): centre of mass, its velocity, orientation (body -> world) and
// angular momentum about the centre, both vectors in world axes.
struct RockState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();          // m
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();          // m/s
  Eigen::Quaterniond orientation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d angular_momentum = Eigen::Vector3d::Zero();  // kg m2/s
};

// w = R I^-1 R^T L (rad/s, world) at the state's orientation.
Eigen::Vector3d angular_velocity(const RigidRock& rock, const RockState& state);
// 1/2 m |v|^2 + 1/2 L . w (J).
double kinetic_energy(const RigidRock& rock, const RockState& state);
// The state of a rock released from a rigid-body state (spin w gives L = R I R^T w).
RockState rock_state(const RigidRock& rock, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                     const Eigen::Quaterniond& orientation, const Eigen::Vector3d& angular_velocity);

// Kick: the momenta change by a force (N) and a torque (N m) acting for `duration` seconds.
void kick(RockState& state, double mass, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
          double duration);
// Drift (paper 3.1, free motion at fixed momenta over `duration` seconds): x += v dt, and the
// orientation turns by exp(w dt / 2) q with the spin w at the step's middle orientation.
void drift(const RigidRock& rock, RockState& state, double duration);

}  // namespace talus
