// The rock against the piston carpet (paper 3.3, steps 1-4): implicit-function test of each
// piston top, bisection along the piston axis to the rock's surface, the stress-cycle response
// along the deformed ground's normal, and Coulomb and vegetation friction.
#include "talus/rockfall/piston_contact.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Cholesky>

namespace talus {
namespace {

// Paper 3.3, step 3 for a piston the rock no longer presses: it rises back to its footprint,
// where its pressure is zero and its state keeps the footprint (stress_cycle.hpp).
void release(Piston& piston, double footprint, std::vector<PistonChange>& journal) {
  if (!(piston.state.compression > footprint)) return;
  journal.push_back({piston.i, piston.j, piston.state});
  press(piston.cycle, piston.state, footprint);
}

bool holds(const CarpetWindow& window, std::int64_t i, std::int64_t j) {
  return i >= window.i_begin && i < window.i_end && j >= window.j_begin && j < window.j_end;
}

// Paper 3.3, step 2: for a top inside the rock (body frame, m), the distance (m) along the unit
// axis (body frame) to where the axis leaves the rock: bisection on the rock's function over
// [0, exit], exit where the axis leaves the rock's bounding sphere (below the rock, so outside it).
double depth_below_surface(const RigidRock& rock, const Eigen::Vector3d& top_body, const Eigen::Vector3d& axis_body,
                           const PistonContactParameters& parameters) {
  const double radius = rock.bounding_radius();
  const double along = top_body.dot(axis_body);
  const double exit = along + std::sqrt(std::max(0.0, along * along + radius * radius - top_body.squaredNorm()));
  double inside = 0.0;
  double outside = exit + parameters.bisection_tolerance;
  for (int k = 0; k < parameters.bisection_iterations && outside - inside > parameters.bisection_tolerance; ++k) {
    const double middle = 0.5 * (inside + outside);
    if (rock.value(top_body - middle * axis_body) < 0.0) {
      inside = middle;
    } else {
      outside = middle;
    }
  }
  return 0.5 * (inside + outside);
}

}  // namespace

Eigen::Vector3d NormalResponse::centroid() const {
  Eigen::Vector3d weighted = Eigen::Vector3d::Zero();
  double sum = 0.0;
  for (const PistonTouch& touch : touches) {
    weighted += touch.load * touch.arm;
    sum += touch.load;
  }
  return sum > 0.0 ? Eigen::Vector3d(weighted / sum) : Eigen::Vector3d::Zero();
}

void PistonRange::gather(PistonCarpet& carpet, const CarpetWindow& range) {
  window = range;
  pistons.clear();
  for (std::int64_t j = range.j_begin; j < range.j_end; ++j) {
    for (std::int64_t i = range.i_begin; i < range.i_end; ++i) {
      Piston& piston = carpet.at(i, j);
      if (piston.valid) pistons.push_back(&piston);
    }
  }
}

// Paper fig. 2: the slope of the branch the piston is on (Pa/m). On the loading curve its
// compression is its largest; k1 below the yield pressure, k2 above; k3 below d_max.
double active_slope(const StressCycle& cycle, const PistonState& state) {
  if (state.compression < state.max_compression) return cycle.unloading_slope;
  return cycle.elastic_slope * state.compression <= cycle.yield_pressure ? cycle.elastic_slope : cycle.plastic_slope;
}

// Paper 3.3, steps 1-3. A piston whose top t(d) = rest_top - d axis, at its footprint d_res, lies
// inside the rock is pushed to the compression d where t(d) is on the rock's surface: bisection
// on the rock's function f over [d_res, d_exit], d_exit where t(d) leaves the rock's bounding
// sphere (below the rock, so outside it). Its pressure p acts on its cross-section
// A along n = -g, g the rock's outward unit normal at t(d); the force p A n / |g . axis| is
// minus the gradient of the piston's energy with respect to the rock's motion, because moving
// the rock by dx changes d by g . dx / |g . axis| (docs/rockfall-full.md, section 3). Under a
// fragment, d is at most D / c, D = depth_inside at the rest top r and c the grazing cosine: where
// that bound holds, moving the rock by dx changes d by -R grad D . dx / c, so the force is
// p A R grad D / c, at r (section 3.5).
void press_carpet(PistonCarpet& carpet, const PistonRange& range, const RigidRock& rock,
                  const Eigen::Vector3d& centre, const Eigen::Matrix3d& rotation,
                  const PistonContactParameters& parameters, const std::vector<PistonTouch>& previous,
                  NormalResponse& response, std::vector<PistonChange>& journal) {
  response.force.setZero();
  response.torque.setZero();
  response.stiffness = 0.0;
  response.rotational_stiffness = 0.0;
  response.elastic_energy = 0.0;
  response.dissipated = 0.0;
  response.touches.clear();
  response.near.clear();

  for (const PistonTouch& touch : previous) {
    if (holds(range.window, touch.i, touch.j) || !holds(carpet.window(), touch.i, touch.j)) continue;
    Piston& piston = carpet.at(touch.i, touch.j);
    release(piston, piston.cycle.residual_compression(piston.state.max_compression), journal);
  }

  const Eigen::Matrix3d to_body = rotation.transpose();
  const double radius = rock.bounding_radius();
  const double radius_squared = radius * radius;
  for (Piston* candidate : range.pistons) {
    Piston& piston = *candidate;
    const double footprint = piston.cycle.residual_compression(piston.state.max_compression);
    const Eigen::Vector3d offset = piston.rest_top - footprint * piston.axis - centre;
    const double distance_squared = offset.squaredNorm();
    if (distance_squared >= radius_squared) {
      release(piston, footprint, journal);
      response.near.push_back({offset, piston.axis, std::sqrt(distance_squared) - radius});
      continue;
    }
    const Eigen::Vector3d top_body = to_body * offset;
    const double value = rock.value(top_body);
    if (!(value < 0.0)) {
      release(piston, footprint, journal);
      response.near.push_back({offset, piston.axis, value * rock.inner_radius()});
      continue;
    }
    const Eigen::Vector3d axis_body = to_body * piston.axis;
    const double depth = depth_below_surface(rock, top_body, axis_body, parameters);
    double compression = footprint + depth;
    // A fragment's cut faces (docs/rockfall-full.md, section 3.5): the compression is at most how
    // deep the rest top lies below the surface over the grazing cosine; in the recovery (section
    // 5) under every rock, with -f x inner_radius as the depth below its outer surface.
    const Eigen::Vector3d rest_offset = piston.rest_top - centre;
    const Eigen::Vector3d rest_body = to_body * rest_offset;
    Eigen::Vector3d inwards = Eigen::Vector3d::Zero();
    double sideways = rock.depth_inside(rest_body, inwards) / parameters.grazing_cosine;
    if (parameters.bound_every_compression && !rock.has_cut_faces()) {
      sideways = -rock.value(rest_body) * rock.inner_radius() / parameters.grazing_cosine;
      inwards = -rock.inner_radius() * rock.gradient(rest_body);
    }
    const bool lateral = sideways < compression && inwards.norm() > 0.0;
    if (lateral) compression = sideways;
    journal.push_back({piston.i, piston.j, piston.state});
    const double dissipated_before = dissipated_energy(piston.cycle, piston.state);
    const double p = press(piston.cycle, piston.state, compression);
    response.dissipated += (dissipated_energy(piston.cycle, piston.state) - dissipated_before) * piston.area;
    if (!(p > 0.0)) continue;

    PistonTouch touch;
    touch.i = piston.i;
    touch.j = piston.j;
    double cosine = 1.0;  // metres of the rock's motion along touch.normal per metre of compression (-)
    if (lateral) {
      // The compression is depth_inside / grazing cosine at the rest top, fixed in the ground.
      const Eigen::Vector3d pushed = rotation * inwards;
      touch.arm = rest_offset;
      touch.normal = pushed.normalized();
      cosine = parameters.grazing_cosine / pushed.norm();
    } else {
      Eigen::Vector3d outward = rotation * rock.gradient(top_body - depth * axis_body);
      const double outward_norm = outward.norm();
      outward = outward_norm > 0.0 ? Eigen::Vector3d(outward / outward_norm) : Eigen::Vector3d(-piston.axis);
      touch.arm = offset - depth * piston.axis;
      touch.normal = -outward;
      cosine = std::max(std::abs(outward.dot(piston.axis)), parameters.grazing_cosine);
    }
    touch.load = p * piston.area / cosine;
    touch.friction = piston.friction;
    touch.rolling_friction = piston.rolling_friction;
    touch.vegetation_deperdition = piston.vegetation_deperdition;
    const Eigen::Vector3d force = touch.load * touch.normal;
    response.force += force;
    response.torque += touch.arm.cross(force);
    const double stiffness = active_slope(piston.cycle, piston.state) * piston.area / (cosine * cosine);
    response.stiffness += stiffness;
    response.rotational_stiffness += stiffness * touch.arm.cross(touch.normal).squaredNorm();
    response.elastic_energy += stored_energy(piston.cycle, piston.state) * piston.area;
    response.touches.push_back(touch);
  }
}

// Paper 3.3, step 4, one linearly implicit kick. With u = (v, w) after the kick, G_i u the slip at
// touch i (G_i = P_i [1, -[r_i]x], P_i the projection across its normal) and M = diag(m 1, I_w),
// the kick M u = M u* - dt sum c_i G_i^T G_i u is solved for u; the impulse is M (u - u*), and
// touch i's force -c_i G_i u.
FrictionImpulse friction_impulse(const std::vector<PistonTouch>& touches, const Eigen::Vector3d& velocity,
                                 const Eigen::Vector3d& spin, double mass, const Eigen::Matrix3d& world_inertia,
                                 double slip_speed, double rolling_resistance, double duration,
                                 std::vector<Eigen::Vector3d>* touch_forces) {
  using Matrix6d = Eigen::Matrix<double, 6, 6>;
  using Vector6d = Eigen::Matrix<double, 6, 1>;
  using SlipMap = Eigen::Matrix<double, 3, 6>;
  Matrix6d friction = Matrix6d::Zero();  // sum of c_i G_i^T G_i (N s/m, N s, N m s)
  std::vector<std::pair<double, SlipMap>> coulomb;  // c_i and G_i, kept for touch_forces
  bool sliding = false;
  for (const PistonTouch& touch : touches) {
    const Eigen::Matrix3d across = Eigen::Matrix3d::Identity() - touch.normal * touch.normal.transpose();
    Eigen::Matrix3d arm_cross;
    arm_cross << 0.0, -touch.arm.z(), touch.arm.y(), touch.arm.z(), 0.0, -touch.arm.x(), -touch.arm.y(),
        touch.arm.x(), 0.0;
    SlipMap slip_map;
    slip_map << across, -across * arm_cross;
    const double slip = (slip_map.leftCols<3>() * velocity + slip_map.rightCols<3>() * spin).norm();
    const double coefficient = touch.friction * touch.load / std::max(slip_speed, slip);
    if (coefficient > 0.0) {
      friction.noalias() += coefficient * slip_map.transpose() * slip_map;
      sliding = true;
    }
    if (touch_forces != nullptr) coulomb.emplace_back(coefficient, slip_map);
    // Rolling resistance: the "slip" is the rolling speed l |w_t| of the centre over the contact.
    const double lever = std::abs(touch.arm.dot(touch.normal));
    const Eigen::Matrix3d rolling_map = lever * across;
    const double rolling = (rolling_map * spin).norm();
    const double rolling_coefficient = rolling_resistance * touch.rolling_friction * touch.load / std::max(slip_speed, rolling);
    if (rolling_coefficient > 0.0) {
      friction.bottomRightCorner<3, 3>().noalias() += rolling_coefficient * rolling_map.transpose() * rolling_map;
      sliding = true;
    }
  }
  if (touch_forces != nullptr) touch_forces->assign(touches.size(), Eigen::Vector3d::Zero());
  FrictionImpulse impulse;
  if (!sliding) return impulse;
  Matrix6d inertia = Matrix6d::Zero();
  inertia.topLeftCorner<3, 3>() = mass * Eigen::Matrix3d::Identity();
  inertia.bottomRightCorner<3, 3>() = world_inertia;
  Vector6d before;
  before << velocity, spin;
  const Vector6d momentum = inertia * before;
  const Vector6d after = (inertia + duration * friction).ldlt().solve(momentum);
  const Vector6d change = inertia * after - momentum;
  impulse.linear = change.head<3>();
  impulse.angular = change.tail<3>();
  if (touch_forces != nullptr) {
    for (std::size_t i = 0; i < coulomb.size(); ++i) (*touch_forces)[i] = -coulomb[i].first * (coulomb[i].second * after);
  }
  return impulse;
}

Eigen::Vector3d vegetation_force(const std::vector<PistonTouch>& touches, const Eigen::Vector3d& velocity,
                                 double mass) {
  double total_load = 0.0;
  double weighted = 0.0;  // sum of c N (N/m)
  for (const PistonTouch& touch : touches) {
    total_load += touch.load;
    weighted += touch.vegetation_deperdition * touch.load;
  }
  if (!(total_load > 0.0) || !(weighted > 0.0)) return Eigen::Vector3d::Zero();
  return -(weighted / total_load) * mass * velocity.norm() * velocity;
}

}  // namespace talus
