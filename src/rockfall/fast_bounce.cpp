// Fast bounce mode (paper 3.3, "Fast Bounce mode"): one rock from release to rest on one
// perturbed ground. Flight (flight.hpp) between ground checks that never skip a node line of the
// DEM, ground crossings located in time, the fast bounce impulse (fast_bounce_impact.hpp), and
// the rolling/sliding phase (surface_contact.hpp) with its take-off rule and stop rules.
#include "talus/rockfall/fast_bounce.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>

#include "talus/core/errors.hpp"
#include "talus/rockfall/fast_bounce_impact.hpp"
#include "talus/rockfall/flight.hpp"
#include "talus/rockfall/rolling.hpp"
#include "talus/rockfall/surface_contact.hpp"

namespace talus {
namespace {

constexpr double kTimeTolerance = 1e-9;      // s: a landing is located within this time...
constexpr double kLandingTolerance = 1e-6;   // m: ...or within this height above the ground
constexpr double kRiseTolerance = 0.5;       // of contact_tolerance: how closely a rise is located
constexpr int kMaxCrossingIterations = 200;
constexpr double kNodeLineMargin = 1e-4;   // cells: a step ending this close before a node line reached it
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Issue 18, item 4: kStallSteps steps in a row, each advancing the clock by less than
// kStallStep, are a trajectory that no longer makes progress (within the parameters' ranges no
// legitimate run of steps is that short; docs/rockfall-fast.md, "Bounded work").
constexpr double kStallStep = 1e-9;  // s
constexpr long kStallSteps = 10000;

// Paper 3.3, "Fast Bounce mode", step 1 (collision test), located in time: the last time in
// [a, b] at which the clearance f is still >= 0, given f(a) = fa >= 0 > f(b) = fb. Illinois
// false position (the stale end's weight halved), with bisection when the estimate leaves the
// bracket; stops when the bracket is shorter than kTimeTolerance or f(a) <= height_tolerance.
template <class Clearance>
double last_time_above(const Clearance& f, double a, double fa, double b, double fb, double height_tolerance) {
  double weight_a = fa;
  double weight_b = fb;
  int kept = 0;  // +1: a moved last, -1: b moved last
  for (int i = 0; i < kMaxCrossingIterations && b - a > kTimeTolerance && fa > height_tolerance; ++i) {
    double c = (a * weight_b - b * weight_a) / (weight_b - weight_a);
    if (!(c > a && c < b)) c = 0.5 * (a + b);
    const double fc = f(c);
    if (fc >= 0.0) {
      a = c;
      fa = weight_a = fc;
      if (kept == 1) weight_b *= 0.5;
      kept = 1;
    } else {
      b = c;
      weight_b = fc;
      if (kept == -1) weight_a *= 0.5;
      kept = -1;
    }
  }
  return a;
}

// Time (s) until the continuous node coordinate u, changing at `rate` (1/s), reaches the next
// node line ahead of it.
double time_to_node_line(double u, double rate) {
  if (rate > 0.0) return (std::floor(u + kNodeLineMargin) + 1.0 - u) / rate;
  if (rate < 0.0) return (u - (std::ceil(u - kNodeLineMargin) - 1.0)) / -rate;
  return kInfinity;
}

class FastBounceRun {
 public:
  FastBounceRun(const FastBounceParameters& parameters, const PerturbedGround& ground, const Rock& rock,
                const RigidBodyState& start, TrajectoryObserver& observer)
      : parameters_(parameters),
        ground_(ground),
        rock_(rock),
        observer_(observer),
        mass_(rock.mass()),
        inertia_(rock.inertia()),
        sphere_share_(rolling_share({mass_, inertia_, rock.bounding_radius()}, Eigen::Vector3d::UnitZ(),
                                    Eigen::Vector3d::UnitX())),
        diameter_(std::cbrt(6.0 * rock.volume() / std::numbers::pi)),
        oriented_(rock.shape != BlockShape::sphere),
        flight_(parameters.gravity, AirDrag{parameters.air_density, parameters.drag_coefficient, rock.frontal_area()},
                mass_),
        step_length_(std::min({parameters.max_step_length, parameters.sample_spacing,
                               0.25 * std::min(ground.model().spec().cell_width(),
                                               ground.model().spec().cell_height())})),
        p_(start.position),
        v_(start.velocity),
        q_(start.orientation.normalized()),
        w_(start.angular_velocity),
        h_(rock.half_height(q_)) {}

  StopReason run() {
    std::optional<StopReason> stop = begin();
    while (!stop) {
      const double before = t_;
      stop = in_flight_ ? flight_step() : contact_step();
      watch_progress(t_ - before);
    }
    if (unsampled_) report_sample();
    observer_.on_stop(sample(), *stop);
    return *stop;
  }

 private:
  // --- the three phases ---------------------------------------------------------------------

  // Release (paper 3.4: one trajectory from its release point): a contact point below the
  // ground (or within contact_tolerance above it) is put on the ground; a rock touching the
  // ground then leaves it, bounces (paper 3.3), or starts in contact.
  std::optional<StopReason> begin() {
    if (!ground_.contains(p_.x(), p_.y())) {
      ground_z_ = p_.z();
      report_sample();
      return outside(p_);
    }
    const GroundPoint point = ground_.at(p_.x(), p_.y());
    ground_z_ = point.height;
    clearance_ = p_.z() - h_ - ground_z_;
    if (clearance_ <= parameters_.contact_tolerance) {
      p_.z() = ground_z_ + h_;
      clearance_ = 0.0;
    }
    report_sample();
    if (clearance_ > 0.0) return std::nullopt;
    const double v_normal = v_.dot(point.normal);
    if (v_normal >= parameters_.contact_speed) {
      hop_limit_ = v_normal / (parameters_.gravity * point.normal.z());
    } else if (-v_normal >= parameters_.contact_speed) {
      land(point, false);
    } else {
      touch_down(point, p_, 0.0, 0.0);
    }
    return std::nullopt;
  }

  // Flight (paper 3.2) to the next ground check; a contact point found below the ground is
  // traced back to the crossing, where the rock lands.
  std::optional<StopReason> flight_step() {
    if (t_ >= parameters_.max_time) return StopReason::max_time;
    const PointState from{p_, v_};
    const double dt = flight_duration();
    const PointState end = flight_.advance(from, dt);
    if (!ground_.contains(end.position.x(), end.position.y())) return outside(end.position);
    const Eigen::Quaterniond q_end = rotated(dt);
    const double h_end = half_height(q_end);
    const double z_end = ground_.height(end.position.x(), end.position.y());
    const double clearance = end.position.z() - h_end - z_end;
    if (clearance >= 0.0) {
      move_to(end, q_end, h_end, dt);
      ground_z_ = z_end;
      clearance_ = clearance;
      sample_if_due();
      return std::nullopt;
    }
    const FlightArc arc(from, end, dt);
    const auto clearance_at = [&](double tau) {
      const Eigen::Vector3d x = arc.position(tau);
      return x.z() - half_height_after(tau) - ground_.height(x.x(), x.y());
    };
    const double tau = last_time_above(clearance_at, 0.0, clearance_, dt, clearance, kLandingTolerance);
    const Eigen::Quaterniond q_touch = rotated(tau);
    move_to(arc.at(tau), q_touch, half_height(q_touch), tau);
    land(ground_.at(p_.x(), p_.y()), true);
    return std::nullopt;
  }

  // One step of the rolling/sliding phase that lets fast-mode rocks come to rest (paper 3.3;
  // Coulomb and vegetation friction of paper 2.1; rolling resistance of Azzoni et al. 1995):
  // constant acceleration along the surface, stop rules, take-off where the ground falls away,
  // and a new contact where it rises. The rock rolls where the sliding friction can hold its
  // contact point, and slides without spin elsewhere (docs/rockfall-fast.md, section 5).
  std::optional<StopReason> contact_step() {
    if (t_ >= parameters_.max_time) return StopReason::max_time;
    const double speed = v_.norm();
    const GroundMaterial material = under_.material;
    const Eigen::Vector3d& n = under_.normal;
    const double lower_friction = std::min(material.friction, material.rolling_friction);
    if (speed < parameters_.stop_speed && friction_holds(n, lower_friction)) return StopReason::at_rest;
    if (speed == 0.0) {
      // Restart from rest down the fall line; a rock that comes back to rest within its own
      // diameter of its last restart is caught in a hollow between slopes too steep to hold it.
      const Eigen::Vector2d here = p_.head<2>();
      if (has_restart_ && (here - restart_xy_).norm() < diameter_) return StopReason::at_rest;
      has_restart_ = true;
      restart_xy_ = here;
    }
    // Azzoni et al. 1995: a rolling rock accelerates at A (g_t - mu_r g n_z v/|v| - c |v| v); a
    // sliding one at g_t - mu g n_z v/|v| - c |v| v, as a block without spin (A = 1).
    const Eigen::Vector3d fall_line = Eigen::Vector3d::UnitZ() - n.z() * n;
    const double rolling =
        oriented_ ? rolling_share(rolling_body(q_, h_), n, speed > 0.0 ? v_ : Eigen::Vector3d(-fall_line)) : sphere_share_;
    const bool rolls = rolls_without_slip(rolling, n.head<2>().norm() / n.z(), material.friction, material.rolling_friction);
    change_contact_motion(rolls);
    const double share = rolls ? rolling : 1.0;
    const double resistance = rolls ? material.rolling_friction : material.friction;
    const Eigen::Vector3d a = share * contact_acceleration(v_, n, resistance, material.vegetation_deperdition,
                                                           parameters_.gravity);
    const double dt = std::min({parameters_.contact_time_step, duration_for_length(speed, a.norm(), step_length_),
                                parameters_.max_time - t_});
    SurfaceMove move = move_on_surface(v_, a, dt);
    Eigen::Vector3d end = p_ + move.displacement;
    if (!ground_.contains(end.x(), end.y())) return outside(end);
    Eigen::Quaterniond q_end = rotated(move.duration);
    double h_end = half_height(q_end);
    GroundPoint point = ground_.at(end.x(), end.y());
    const double gap = end.z() - h_end - point.height;
    if (gap < -parameters_.contact_tolerance) {
      // The ground rose above the rock's path: the step ends where the rise reaches the tolerance.
      const double tolerance = parameters_.contact_tolerance;
      const auto rise_margin = [&](double tau) {
        const Eigen::Vector3d x = p_ + tau * v_ + 0.5 * tau * tau * a;
        return x.z() - half_height_after(tau) - ground_.height(x.x(), x.y()) + tolerance;
      };
      const double tau = last_time_above(rise_margin, 0.0, tolerance, move.duration, gap + tolerance,
                                         kRiseTolerance * tolerance);
      move = move_on_surface(v_, a, tau);
      end = p_ + move.displacement;
      q_end = rotated(move.duration);
      h_end = half_height(q_end);
      point = ground_.at(end.x(), end.y());
    }
    const bool takes_off = gap > parameters_.contact_tolerance && flight_clears(move.duration, h_end);
    // Work of the rolling resistance or sliding friction (exact on a plane) and of the vegetation
    // over the step.
    const double distance = move.displacement.norm();
    const double mean_square_speed = 0.5 * (speed * speed + move.velocity.squaredNorm());
    const double friction_work = mass_ * distance *
                                 (resistance * parameters_.gravity * n.z() +
                                  material.vegetation_deperdition * mean_square_speed);
    const Eigen::Vector3d midpoint = p_ + 0.5 * move.displacement;
    if (!takes_off) {
      // Back onto the surface: the lift (or drop) off the tangent plane costs (or gives) m g dz
      // of the rock's kinetic energy 1/2 m |v|^2 / A (A = 1 sliding), so that following bumps and
      // hollows creates no energy.
      const double lift = point.height + h_end - end.z();
      const double square_speed = move.velocity.squaredNorm();
      if (square_speed > 0.0) {
        const double kept = square_speed - 2.0 * share * parameters_.gravity * lift;
        move.velocity *= kept > 0.0 ? std::sqrt(kept / square_speed) : 0.0;
      }
      end.z() += lift;
    }
    move_to({end, move.velocity}, q_end, h_end, move.duration);
    ground_z_ = point.height;
    if (takes_off) {
      // The rock leaves the surface where the step ends, above the ground that fell away.
      report_loss(midpoint, friction_work, 0.0);
      clearance_ = gap;
      in_flight_ = true;
      report_sample();
      return std::nullopt;
    }
    if (-v_.dot(point.normal) * point.material.restitution_normal >= parameters_.contact_speed) {
      report_loss(midpoint, friction_work, 0.0);
      land(point, true);
      return std::nullopt;
    }
    keep_contact(point, midpoint, friction_work, share, rolls);
    sample_if_due();
    return std::nullopt;
  }

  // --- transitions --------------------------------------------------------------------------

  // Paper 3.3, "Fast Bounce mode", step 2: the rock is moved up to touch the ground at `point`
  // (the ground under it) and the impulse reflects its velocity; a rebound slower than
  // contact_speed leaves it in contact. A touchdown slower than contact_speed along the normal
  // is no impact: the rock touches down and rolls. A rebound leaves with the rolling spin of its
  // tangential velocity, and no more kinetic energy (translation and rotation) than the rock
  // brought less the vegetation's share: the tangential velocity is scaled down where the spin
  // would need more (docs/rockfall-fast.md, section 4).
  void land(const GroundPoint& point, bool report_arrival) {
    ground_z_ = point.height;
    p_.z() = ground_z_ + h_;
    clearance_ = 0.0;
    unsampled_ = true;
    if (report_arrival) report_sample();
    const Eigen::Vector3d& n = point.normal;
    if (-v_.dot(n) < parameters_.contact_speed) {
      touch_down(point, p_, 0.0, 0.0);
    } else {
      const double brought = kinetic_energy();
      const ImpactResponse response = fast_bounce_impact(v_, n, point.material, mass_, diameter_);
      v_ = response.velocity;
      if (response.normal_speed < parameters_.contact_speed) {
        touch_down(point, p_, response.friction_loss, response.deformation_loss);
      } else {
        const RollingBody body = rolling_body(q_, h_);
        const Eigen::Vector3d tangential = v_ - v_.dot(n) * n;
        const double normal_energy = 0.5 * mass_ * response.normal_speed * response.normal_speed;
        const double tangential_energy = 0.5 * mass_ * tangential.squaredNorm() +
                                         rotation_energy(body, rolling_spin(h_, n, tangential));
        const double allowed = brought - response.friction_loss - normal_energy;
        if (tangential_energy > allowed) v_ -= (1.0 - std::sqrt(std::max(0.0, allowed) / tangential_energy)) * tangential;
        w_ = rolling_spin(h_, n, v_ - v_.dot(n) * n);
        report_loss(p_, response.friction_loss, brought - response.friction_loss - kinetic_energy());
        in_flight_ = true;
        hop_limit_ = response.normal_speed / (parameters_.gravity * n.z());
      }
    }
    unsampled_ = true;
    report_sample();
  }

  // The rock comes into contact at `point` from a flight, a release or a rebound too slow to
  // leave: it loses its normal velocity (a deformation loss) and starts to roll, its tangential
  // velocity and spin becoming rolling without slip by friction at the contact point
  // (start_rolling, a friction loss). The caller's losses are reported with them.
  void touch_down(const GroundPoint& point, const Eigen::Vector3d& at, double friction, double deformation) {
    const double v_normal = v_.dot(point.normal);
    v_ -= v_normal * point.normal;
    const RollingBody body = rolling_body(q_, h_);
    const double before = translation_energy() + rotation_energy(body, w_);
    v_ = start_rolling(body, point.normal, v_, w_);
    w_ = rolling_spin(h_, point.normal, v_);
    rolling_ = true;
    report_loss(at, friction + before - kinetic_energy(), deformation + 0.5 * mass_ * v_normal * v_normal);
    enter_contact(point);
  }

  // Paper 3.3, fast mode's contact, from one step to the next: the rock stays on the surface at
  // `point`, rolling or sliding; it loses the part of its velocity along the new normal, which
  // takes the energy 1/2 m v_n^2 / A with it (A = 1 sliding; reported as deformation, with the
  // step's friction work).
  void keep_contact(const GroundPoint& point, const Eigen::Vector3d& at, double friction, double share, bool rolls) {
    const double v_normal = v_.dot(point.normal);
    v_ -= v_normal * point.normal;
    w_ = rolls ? rolling_spin(h_, point.normal, v_) : Eigen::Vector3d::Zero();
    report_loss(at, friction, 0.5 * mass_ * v_normal * v_normal / share);
    enter_contact(point);
  }

  // Between rolling and sliding (docs/rockfall-fast.md, section 5): a rock that starts to slide
  // gives up its spin (a friction loss); one that starts to roll again does so as a touchdown
  // does (start_rolling).
  void change_contact_motion(bool rolls) {
    if (rolls == rolling_) return;
    rolling_ = rolls;
    const double before = kinetic_energy();
    if (rolls) {
      v_ = start_rolling(rolling_body(q_, h_), under_.normal, v_, w_);
      w_ = rolling_spin(h_, under_.normal, v_);
    } else {
      w_ = Eigen::Vector3d::Zero();
    }
    report_loss(p_, before - kinetic_energy(), 0.0);
  }

  void enter_contact(const GroundPoint& point) {
    under_ = point;
    in_flight_ = false;
    clearance_ = 0.0;
  }

  // Take-off rule over a convex break (paper 3.3, fast mode): the free flight (paper 3.2) from
  // the step's start state would end more than contact_tolerance above the ground, so the
  // ground fell away faster than gravity can keep the rock on it.
  bool flight_clears(double duration, double h_end) const {
    const PointState flown = flight_.advance({p_, v_}, duration);
    if (!ground_.contains(flown.position.x(), flown.position.y())) return false;
    return flown.position.z() - h_end - ground_.height(flown.position.x(), flown.position.y()) >
           parameters_.contact_tolerance;
  }

  // --- helpers ------------------------------------------------------------------------------

  // Issue 18, item 4: a trajectory whose steps stopped advancing the clock throws
  // NumericalFailure (exit code 3, naming the rock's place) instead of looping for ever.
  void watch_progress(double step) {
    stalled_steps_ = step < kStallStep ? stalled_steps_ + 1 : 0;
    if (stalled_steps_ < kStallSteps) return;
    char message[256];
    std::snprintf(message, sizeof message,
                  "fast bounce: the trajectory stalled (%ld steps in a row shorter than %g s) at t = %.6g s, centre "
                  "(%.3f, %.3f, %.3f) m",
                  kStallSteps, kStallStep, t_, p_.x(), p_.y(), p_.z());
    throw NumericalFailure(message);
  }

  // Flight step between ground checks (paper 3.3, step 1; creases of the paper 2.2 surface): at
  // most step_length_ of path, never past the next node line of the DEM (the bilinear surface's
  // creases, where ridges and cliff edges are), within RK4's accuracy bound, no further than the
  // apex of a fresh bounce, and not past max_time.
  double flight_duration() {
    const GridSpec& spec = ground_.model().spec();
    const double to_line = std::min(time_to_node_line(spec.col_of(p_.x()), v_.x() / spec.geotransform[1]),
                                    time_to_node_line(spec.row_of(p_.y()), v_.y() / spec.geotransform[5]));
    const double dt = std::min({duration_for_length(v_.norm(), flight_.acceleration_bound(v_), step_length_),
                                flight_.max_duration(v_), to_line, hop_limit_, parameters_.max_time - t_});
    hop_limit_ = kInfinity;
    return dt;
  }

  // Orientation after `duration` seconds of constant spin (spheres need none).
  Eigen::Quaterniond rotated(double duration) const {
    if (!oriented_) return q_;
    const double angle = w_.norm() * duration;
    if (angle == 0.0) return q_;
    return Eigen::Quaterniond(Eigen::AngleAxisd(angle, w_.normalized())) * q_;
  }
  double half_height(const Eigen::Quaterniond& q) const { return oriented_ ? rock_.half_height(q) : h_; }
  // Half height after `duration` seconds of spin, for the crossing searches' trial times.
  double half_height_after(double duration) const { return oriented_ ? rock_.half_height(rotated(duration)) : h_; }

  void move_to(const PointState& state, const Eigen::Quaterniond& q, double h, double duration) {
    travelled_ += (state.position - p_).norm();
    p_ = state.position;
    v_ = state.velocity;
    q_ = q;
    h_ = h;
    t_ += duration;
    unsampled_ = true;
  }

  StopReason outside(const Eigen::Vector3d& at) const { return reason_for_leaving(ground_.model().spec(), at); }

  // The rock as rolling sees it at orientation q, its contact point h below its centre. A
  // sphere's inertia is the same in every frame.
  RollingBody rolling_body(const Eigen::Quaterniond& q, double h) const {
    if (!oriented_) return {mass_, inertia_, h};
    const Eigen::Matrix3d rotation = q.toRotationMatrix();
    return {mass_, rotation * inertia_ * rotation.transpose(), h};
  }
  double translation_energy() const { return 0.5 * mass_ * v_.squaredNorm(); }
  // Translation and rotation (J), as hazard practice counts a rock's energy.
  double kinetic_energy() const { return translation_energy() + rotation_energy(rolling_body(q_, h_), w_); }

  TrajectorySample sample() const { return {t_, p_, v_, kinetic_energy(), p_.z() - ground_z_}; }
  void report_sample() {
    observer_.on_sample(sample());
    travelled_ = 0.0;
    unsampled_ = false;
  }
  // A sample before the next step could take the path past sample_spacing.
  void sample_if_due() {
    if (travelled_ + step_length_ > parameters_.sample_spacing) report_sample();
  }
  void report_loss(const Eigen::Vector3d& at, double friction, double deformation) {
    if (friction > 0.0 || deformation > 0.0) observer_.on_energy_loss(at.x(), at.y(), friction, deformation);
  }

  const FastBounceParameters& parameters_;
  const PerturbedGround& ground_;
  const Rock& rock_;
  TrajectoryObserver& observer_;
  const double mass_;          // kg
  const Eigen::Matrix3d inertia_;  // kg m2 about the centre, local frame
  const double sphere_share_;      // Azzoni's A of a sphere (5/7), the same in every direction
  const double diameter_;      // m, of the sphere of the same volume: the vegetation's contact length
  const bool oriented_;        // the half height depends on the orientation
  const Flight flight_;
  const double step_length_;   // m: longest path between two ground checks

  Eigen::Vector3d p_, v_;      // centre of mass (m), velocity (m/s)
  Eigen::Quaterniond q_;       // orientation
  Eigen::Vector3d w_;          // spin (rad/s)
  double h_;                   // half height at q_ (m)
  double t_ = 0.0;             // s since release
  double ground_z_ = 0.0;      // ground height under p_ (m)
  double clearance_ = 0.0;     // contact point above the ground (m)
  bool in_flight_ = true;
  bool rolling_ = true;        // in contact: rolling (else sliding without spin)
  double hop_limit_ = kInfinity;  // s: first flight step after a bounce ends at its apex at the latest
  GroundPoint under_;          // in contact: the ground under p_
  bool has_restart_ = false;
  Eigen::Vector2d restart_xy_ = Eigen::Vector2d::Zero();
  double travelled_ = 0.0;     // m of path since the last sample
  bool unsampled_ = false;     // the state moved since the last sample
  long stalled_steps_ = 0;     // steps in a row shorter than kStallStep
};

}  // namespace

// Paper 3.3, "Fast Bounce mode": one trajectory from `start` to its stop.
StopReason FastBounce::run(const PerturbedGround& ground, const Rock& rock, RigidBodyState start,
                           TrajectoryObserver& observer) const {
  return FastBounceRun(parameters_, ground, rock, start, observer).run();
}

}  // namespace talus
