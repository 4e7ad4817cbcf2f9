// The full model's rock as a rigid body (paper 3.1): implicit parts in the body frame, mass
// properties integrated over the shape (or summed over the parts of a pre-fractured block,
// paper fig. 4), and the two halves of the kick-drift-kick integrator.
#include "talus/rockfall/rigid_rock.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include <Eigen/Eigenvalues>

namespace talus {
namespace {

constexpr double kMaxSubstepAngle = 0.01;  // rad: largest turn of one drift substep
constexpr double kSkinProbe = 1e-4;        // how far outside a surface sample, in inner radii, the skin test looks (-)

// The rotation by the angle |w| t about w (rad/s, over t seconds) as a unit quaternion: the
// exponential exp(w t / 2) of the pure quaternion (0, w t / 2).
Eigen::Quaterniond rotation_over(const Eigen::Vector3d& w, double duration) {
  const double angle = w.norm() * duration;
  if (angle == 0.0) return Eigen::Quaterniond::Identity();
  return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized()));
}

// w = R I^-1 R^T L (rad/s) for the rotation R (body -> world).
Eigen::Vector3d spin(const RigidRock& rock, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& momentum) {
  return rotation * (rock.inverse_inertia() * (rotation.transpose() * momentum));
}

// Paper 3.1: one part, the rock's implicit shape with its origin moved to the centre of mass
// that integrate_mass finds; mass and inertia from the same integration (uniform density).
RockPart whole_rock(const Rock& rock, int surface_samples, int mass_resolution) {
  const ImplicitShape shape(rock, surface_samples);
  const MassProperties properties = integrate_mass(shape, rock.density, mass_resolution);
  return RockPart{shape.shifted(properties.centre), Eigen::Vector3d::Zero(), properties.mass, properties.inertia};
}

}  // namespace

Eigen::Vector3d centre_of_mass(const std::vector<RockPart>& parts) {
  double mass = 0.0;
  Eigen::Vector3d moment = Eigen::Vector3d::Zero();  // kg m
  for (const RockPart& part : parts) {
    mass += part.mass;
    moment += part.mass * part.offset;
  }
  return moment / mass;
}

double smallest_semi_axis(const Rock& rock) {
  return 0.5 * (rock.shape == BlockShape::sphere ? rock.axes.x() : rock.axes.minCoeff());
}

RigidRock::RigidRock(const Rock& rock, int surface_samples, int mass_resolution)
    : RigidRock(std::vector<RockPart>{whole_rock(rock, surface_samples, mass_resolution)}, smallest_semi_axis(rock)) {}

// Paper 3.1 and fig. 4: the parts moved so that their centre of mass is the body's origin; the
// body's inertia about it is the sum of I_p + m_p (|o|^2 1 - o o^T) over the parts (parallel
// axes), o their offsets. A cut face is on the surface unless a point kSkinProbe x inner_radius
// outside it lies inside another part. The skin of a whole block is the uncut rock's samples;
// otherwise it keeps a part's sample unless the point as far outside it along its normal lies
// inside another part (a face that two parts share).
RigidRock::RigidRock(std::vector<RockPart> parts, double inner_radius)
    : parts_(std::move(parts)), inner_radius_(inner_radius) {
  if (parts_.empty()) throw std::invalid_argument("RigidRock: a body needs at least one part");
  const Eigen::Vector3d centre = centre_of_mass(parts_);
  for (RockPart& part : parts_) {
    part.offset -= centre;
    const Eigen::Vector3d& o = part.offset;
    mass_ += part.mass;
    inertia_ += part.inertia + part.mass * (o.squaredNorm() * Eigen::Matrix3d::Identity() - o * o.transpose());
  }
  if (!(mass_ > 0.0)) throw std::invalid_argument("RigidRock: the rock has no volume");
  inverse_inertia_ = inertia_.inverse();
  const Eigen::Vector3d moments =
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(inertia_, Eigen::EigenvaluesOnly).eigenvalues();
  min_inertia_ = moments.minCoeff();
  anisotropy_ = (moments.maxCoeff() - min_inertia_) / moments.maxCoeff();
  const double probe = kSkinProbe * inner_radius_;
  // Whether a body-frame point lies inside a part other than the p-th.
  const auto in_another = [this](std::size_t p, const Eigen::Vector3d& point) {
    for (std::size_t q = 0; q < parts_.size(); ++q) {
      if (q != p && parts_[q].shape.value(point - parts_[q].offset) < 0.0) return true;
    }
    return false;
  };
  std::vector<std::vector<CutPlane>> faces(parts_.size());
  bool exposed = false;
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    const RockPart& part = parts_[p];
    bounding_radius_ = std::max(bounding_radius_, part.offset.norm() + part.shape.bounding_radius());
    for (const CutPlane& plane : part.cuts) {
      if (in_another(p, part.offset + (plane.offset + probe) * plane.normal)) continue;
      faces[p].push_back(plane);
      exposed = true;
    }
  }
  if (exposed) cut_faces_ = std::move(faces);
  const bool cut = std::any_of(parts_.begin(), parts_.end(), [](const RockPart& part) { return !part.cuts.empty(); });
  const bool known = std::all_of(parts_.begin(), parts_.end(), [](const RockPart& part) { return part.whole.has_value(); });
  whole_ = cut && known && !exposed;
  if (whole_) {
    for (SurfaceSample sample : parts_.front().whole->surface()) {
      sample.position += parts_.front().offset;
      skin_.push_back(sample);
    }
    return;
  }
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    for (SurfaceSample sample : parts_[p].shape.surface()) {
      sample.position += parts_[p].offset;
      if (!in_another(p, sample.position + probe * sample.normal)) skin_.push_back(sample);
    }
  }
}

// Paper 3.1 (implicit surface of a body of several parts): the union of the parts, min of their
// functions. A whole block's union is the uncut rock: outside it, the part whose side of every cut
// holds the point gives the uncut function (its planes are negative there), the others more.
double RigidRock::value(const Eigen::Vector3d& body) const {
  if (whole_) return parts_.front().whole->value(body - parts_.front().offset);
  double f = std::numeric_limits<double>::infinity();
  for (const RockPart& part : parts_) f = std::min(f, part.shape.value(body - part.offset));
  return f;
}

Eigen::Vector3d RigidRock::gradient(const Eigen::Vector3d& body) const {
  if (whole_) return parts_.front().whole->gradient(body - parts_.front().offset);
  const RockPart& nearest = parts_[part_at(body)];
  return nearest.shape.gradient(body - nearest.offset);
}

std::size_t RigidRock::part_at(const Eigen::Vector3d& body) const {
  std::size_t nearest = 0;
  double f = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < parts_.size(); ++p) {
    const double g = parts_[p].shape.value(body - parts_[p].offset);
    if (g < f) {
      f = g;
      nearest = p;
    }
  }
  return nearest;
}

// Paper 3.3 with fig. 4 (docs/rockfall-full.md, section 3.5): a face n.p <= d lies d - n.p away
// from a point p inside it; the uncut rock's function is a gauge that changes by at most
// 1 / inner_radius per metre, so -f x inner_radius is at most the distance to its surface.
double RigidRock::depth_inside(const Eigen::Vector3d& body, Eigen::Vector3d& gradient) const {
  if (cut_faces_.empty()) return std::numeric_limits<double>::infinity();
  const std::size_t p = part_at(body);
  const RockPart& part = parts_[p];
  const Eigen::Vector3d local = body - part.offset;
  double depth = std::numeric_limits<double>::infinity();
  if (part.whole) {
    depth = -part.whole->value(local) * inner_radius_;
    gradient = -inner_radius_ * part.whole->gradient(local);
  }
  for (const CutPlane& face : cut_faces_[p]) {
    const double distance = face.offset - face.normal.dot(local);
    if (distance < depth) {
      depth = distance;
      gradient = -face.normal;
    }
  }
  return depth;
}

// Paper 2.2 (the carpet covers the rock's axis-parallel bounding box): the union of the parts'
// boxes, each around its offset turned into world axes.
Eigen::AlignedBox3d RigidRock::world_bounds(const Eigen::Quaterniond& orientation) const {
  Eigen::AlignedBox3d box;
  for (const RockPart& part : parts_) {
    Eigen::AlignedBox3d part_box = part.shape.world_bounds(orientation);
    part_box.translate(orientation * part.offset);
    box.extend(part_box);
  }
  return box;
}

// Paper 3.2 as surface_drag (implicit_shape.hpp) over the skin: the samples facing the motion
// (n . v > 0) add their projected area a = (v_hat . n) dA; F = -1/2 rho Cx |v| v sum a, acting
// through the centroid of the projected areas, so the moment about the centre is
// (R sum a p / sum a) x F. Faces shared by parts are not in the skin, so a pre-fractured block
// meets the drag of its outer surface only.
Eigen::Vector3d RigidRock::drag(const Eigen::Quaterniond& orientation, const Eigen::Vector3d& velocity,
                                double air_density, double drag_coefficient, Eigen::Vector3d& torque) const {
  torque.setZero();
  const double speed = velocity.norm();
  if (speed == 0.0) return Eigen::Vector3d::Zero();
  const Eigen::Quaterniond rotation = orientation.normalized();
  const Eigen::Vector3d flow_body = rotation.conjugate() * (velocity / speed);
  double projected_area = 0.0;                            // m2
  Eigen::Vector3d area_moment = Eigen::Vector3d::Zero();  // m3, body frame
  for (const SurfaceSample& sample : skin_) {
    const double facing = sample.normal.dot(flow_body);
    if (facing <= 0.0) continue;
    const double area = facing * sample.area;
    projected_area += area;
    area_moment += area * sample.position;
  }
  const Eigen::Vector3d force = -0.5 * air_density * drag_coefficient * projected_area * speed * velocity;
  if (projected_area > 0.0) torque = (rotation * (area_moment / projected_area)).cross(force);
  return force;
}

Eigen::Vector3d angular_velocity(const RigidRock& rock, const RockState& state) {
  return spin(rock, state.orientation.toRotationMatrix(), state.angular_momentum);
}

// Paper 3.1: translation plus rotation, 1/2 m v^2 + 1/2 L . w (J).
double kinetic_energy(const RigidRock& rock, const RockState& state) {
  return 0.5 * rock.mass() * state.velocity.squaredNorm() +
         0.5 * state.angular_momentum.dot(angular_velocity(rock, state));
}

RockState rock_state(const RigidRock& rock, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                     const Eigen::Quaterniond& orientation, const Eigen::Vector3d& angular_velocity) {
  RockState state;
  state.position = position;
  state.velocity = velocity;
  state.orientation = orientation.normalized();
  const Eigen::Matrix3d rotation = state.orientation.toRotationMatrix();
  state.angular_momentum = rotation * (rock.inertia() * (rotation.transpose() * angular_velocity));
  return state;
}

// Paper 3.1, Newton and Euler's laws over a kick: dp = F dt, dL = T dt.
void kick(RockState& state, double mass, const Eigen::Vector3d& force, const Eigen::Vector3d& torque,
          double duration) {
  state.velocity += (duration / mass) * force;
  state.angular_momentum += duration * torque;
}

// Paper 3.1, free motion at fixed momenta: x += v dt; q <- exp(w h / 2) q over substeps h with
// w taken at the orientation reached after half the substep (turned by the substep's starting
// spin), second order like the translation. The spin changes during a free rotation only as
// much as the inertia is anisotropic, (I_max - I_min) / I_max; substeps turn the rock by at most
// kMaxSubstepAngle divided by that, so that a long flight step keeps the free rotation's energy
// to about 1e-6 while a sphere turns in one substep (docs/rockfall-full.md, section 2).
void drift(const RigidRock& rock, RockState& state, double duration) {
  state.position += duration * state.velocity;
  const Eigen::Vector3d& momentum = state.angular_momentum;
  if (momentum.isZero(0.0)) return;
  Eigen::Vector3d w = spin(rock, state.orientation.toRotationMatrix(), momentum);
  const double turn = w.norm() * duration * rock.anisotropy();
  const int substeps = std::max(1, static_cast<int>(std::ceil(turn / kMaxSubstepAngle)));
  const double h = duration / substeps;
  for (int k = 0; k < substeps; ++k) {
    const Eigen::Quaterniond halfway = (rotation_over(w, 0.5 * h) * state.orientation).normalized();
    const Eigen::Vector3d w_middle = spin(rock, halfway.toRotationMatrix(), momentum);
    state.orientation = (rotation_over(w_middle, h) * state.orientation).normalized();
    if (k + 1 < substeps) w = spin(rock, state.orientation.toRotationMatrix(), momentum);
  }
}

}  // namespace talus
