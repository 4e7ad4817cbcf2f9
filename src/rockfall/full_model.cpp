// The paper's full rock-ground model (paper 2.1, 2.2, 3.1-3.3): one rock from release to rest on
// one perturbed ground. The rock (rigid_rock.hpp) moves by kick-drift-kick steps; after every
// drift the piston carpet (piston_carpet.hpp) is scrolled under the rock's bounding box and
// pressed by it (piston_contact.hpp); friction and air drag take the latest velocities. Steps
// follow the contact's stiffness, and the guard (step_guard.hpp) retries blown-up steps with
// halved ones; a step that still fails restarts the rock from its last sound state with shorter
// steps (the recovery of docs/rockfall-full.md, section 5). A pre-fractured block (fracture.hpp)
// checks its bonds after every step; when one breaks, the run ends there and each fragment runs
// on from the break on a copy of the carpet, one after the other. Equations, choices and parameters: docs/rockfall-full.md.
#include "talus/rockfall/full_model.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <deque>
#include <limits>
#include <numbers>
#include <optional>
#include <utility>
#include <vector>

#include "talus/rockfall/fracture.hpp"
#include "talus/rockfall/piston_carpet.hpp"
#include "talus/rockfall/piston_contact.hpp"
#include "talus/rockfall/rigid_rock.hpp"
#include "talus/rockfall/step_guard.hpp"

namespace talus {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
constexpr double kReleaseTolerance = 1e-6;  // m: a rock released into the ground is lifted to touch it within this
// A collapsing step (docs/rockfall-full.md, section 5), as fractions of a fresh contact's step
// time_step_factor x 2 pi sqrt(m / K_fresh) (fresh_contact_step): a step shorter than
// kMinStepFraction of it, or kStallSteps accepted steps in a row each shorter than
// kStallFraction of it, throw NumericalFailure instead of running for ever. The guard's halvings
// and the stiffest contacts keep legitimate steps above 1e-4 of it (measured: 5e-3 at least).
constexpr double kMinStepFraction = 1e-6;
constexpr double kStallFraction = 1e-3;
constexpr long kStallSteps = 10000;
// The recovery (docs/rockfall-full.md, section 5): a sound state is kept every kCheckpointSteps
// accepted steps, and a failed step restarts the rock from the older of the last two, so at least
// kCheckpointSteps back, with the contact steps' rules scaled by kRestartStepScale.
constexpr long kCheckpointSteps = 64;
constexpr double kRestartStepScale = 0.25;

// The pistons of the contact range as the step-size rules see them (docs/rockfall-full.md,
// section 4): their mean axis, how high they reach along it, and how steep they are.
struct CarpetRelief {
  bool has_ground = false;                            // at least one valid piston
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit mean of the pistons' axes
  double reach = -kInfinity;  // m: largest rest top . normal
  double tilt = 0.0;          // largest tangent of the angle between a piston's axis and `normal` (-)
  double stiffest = 0.0;      // Pa/m: largest unloading slope k3
  // m: how far the centre is above the highest rest top, along `normal`.
  double depth(const Eigen::Vector3d& centre) const { return centre.dot(normal) - reach; }
};

// Paper 2.2: the pistons under the rock, summarised once per range.
CarpetRelief relief_of(const PistonRange& range) {
  CarpetRelief relief;
  Eigen::Vector3d axis_sum = Eigen::Vector3d::Zero();
  for (const Piston* piston : range.pistons) axis_sum += piston->axis;
  if (axis_sum.isZero(0.0)) return relief;
  relief.has_ground = true;
  relief.normal = axis_sum.normalized();
  for (const Piston* piston : range.pistons) {
    relief.reach = std::max(relief.reach, piston->rest_top.dot(relief.normal));
    const double cosine = piston->axis.dot(relief.normal);
    relief.tilt = std::max(relief.tilt, std::sqrt(std::max(0.0, 1.0 - cosine * cosine)) / cosine);
    relief.stiffest = std::max(relief.stiffest, piston->cycle.unloading_slope);
  }
  return relief;
}

CarpetWindow widened(const CarpetWindow& window, std::int64_t cells) {
  return {window.i_begin - cells, window.i_end + cells, window.j_begin - cells, window.j_end + cells};
}

bool holds(const CarpetWindow& window, std::int64_t i, std::int64_t j) {
  return i >= window.i_begin && i < window.i_end && j >= window.j_begin && j < window.j_end;
}

bool same_window(const CarpetWindow& a, const CarpetWindow& b) {
  return a.i_begin == b.i_begin && a.i_end == b.i_end && a.j_begin == b.j_begin && a.j_end == b.j_end;
}

// Everything a step changes besides the carpet, so that a failed step can be undone by a copy.
struct RunState {
  RockState rock;
  double time = 0.0;                                        // s since release
  NormalResponse normal;                                    // pistons' response at rock's position
  Eigen::Vector3d vegetation = Eigen::Vector3d::Zero();     // N, with the latest velocity
  Eigen::Vector3d drag_force = Eigen::Vector3d::Zero();     // N
  Eigen::Vector3d drag_torque = Eigen::Vector3d::Zero();    // N m
  CarpetWindow range;                                       // lattice window the contact tests
  CarpetRelief relief;                                      // of its pistons
  double last_step = kInfinity;                             // s
  double deformation_loss = 0.0, friction_loss = 0.0, drag_loss = 0.0;  // J so far
  StepEnergy energy;                                        // J now
};

enum class Attempt { accepted, unsound, outside };

// What a run reports, held back since a checkpoint (docs/rockfall-full.md, section 5, "Recovery"):
// a restart from that checkpoint withdraws them, so the observer sees one consistent trajectory.
class HeldReports {
 public:
  void sample(const TrajectorySample& at) { events_.push_back({Kind::sample, at, 0.0, 0.0, 0.0, 0.0}); }
  void fragment(const TrajectorySample& at) { events_.push_back({Kind::fragment, at, 0.0, 0.0, 0.0, 0.0}); }
  void loss(double x, double y, double friction, double deformation) {
    events_.push_back({Kind::loss, {}, x, y, friction, deformation});
  }
  // Gives the reports to `observer`, in order, and forgets them.
  void pass_to(TrajectoryObserver& observer) {
    for (const Event& e : events_) {
      if (e.kind == Kind::sample) observer.on_sample(e.at);
      if (e.kind == Kind::fragment) observer.on_fragment(e.at);
      if (e.kind == Kind::loss) observer.on_energy_loss(e.x, e.y, e.friction, e.deformation);
    }
    events_.clear();
  }
  void withdraw() { events_.clear(); }

 private:
  enum class Kind { sample, fragment, loss };
  struct Event {
    Kind kind;
    TrajectorySample at;
    double x, y, friction, deformation;
  };
  std::vector<Event> events_;
};

// Where one FullModelRun starts: the block at its release, or a fragment at the break that made it
// (docs/rockfall-full.md, section 11).
struct RunStart {
  FracturedBody block;
  RockState rock;
  double time = 0.0;                   // s since release
  double spacing = 0.0;                // m: piston spacing, the released block's for all its fragments
  std::optional<PistonCarpet> carpet;  // at a break: the block's carpet without the other fragments' loads
  std::vector<PistonTouch> touches;    // at a break: the pistons this fragment loads
  bool announced = false;              // a new fragment for the observer (on_fragment)
};

// How one FullModelRun ended: a stop, or a break into fragments (the first continues the run).
struct RunEnd {
  std::optional<StopReason> stop;
  std::vector<RunStart> fragments;
};

class FullModelRun {
 public:
  FullModelRun(const FullModelParameters& parameters, const PerturbedGround& ground, TrajectoryObserver& observer,
               RunStart start)
      : parameters_(parameters),
        ground_(ground),
        observer_(observer),
        block_(std::move(start.block)),
        body_(block_.body()),
        spacing_(start.spacing),
        margin_cells_(static_cast<std::int64_t>(std::ceil(parameters.carpet_margin / spacing_))),
        contact_{parameters.grazing_cosine, 1e-9, 40},
        carpet_(start.carpet ? std::move(*start.carpet) : PistonCarpet(ground, spacing_)) {
    from_break_ = start.carpet.has_value();
    announced_ = start.announced;
    now_.rock = start.rock;
    now_.time = start.time;
    now_.normal.touches = std::move(start.touches);
  }

  // Runs until the rock stops (then reports the stop and adds its final energies to `balance`) or
  // breaks (then returns its fragments); adds its losses to `balance` either way.
  RunEnd run(EnergyBalance& balance) {
    std::optional<StopReason> stop = begin();
    held_.pass_to(observer_);
    newer_.emplace(sound_state());
    while (!stop && fragments_.empty()) stop = advance();
    balance.deformation_loss += now_.deformation_loss;
    balance.friction_loss += now_.friction_loss;
    balance.drag_loss += now_.drag_loss;
    if (stop && unsampled_) report_sample();
    held_before_.pass_to(observer_);
    held_.pass_to(observer_);
    if (!stop) return {std::nullopt, std::move(fragments_)};
    observer_.on_stop(sample(), *stop);
    balance.kinetic += now_.energy.kinetic;
    balance.potential += now_.energy.potential;
    balance.elastic += now_.energy.elastic;
    return {stop, {}};
  }

 private:
  // --- the run ------------------------------------------------------------------------------

  // Release: the carpet under the rock, a rock released into the ground lifted onto it, the
  // forces on it, the first sample. A fragment starts where the break left it, on the block's
  // carpet, pressing the pistons it loaded.
  std::optional<StopReason> begin() {
    const Eigen::Vector3d& x = now_.rock.position;
    if (!now_.rock.position.allFinite() || !ground_.contains(x.x(), x.y())) {
      if (now_.rock.position.allFinite()) now_.energy = energy_of(now_);
      report_first_sample();
      return outside(x);
    }
    const double inherited = inherited_elastic_energy();
    const double deformation = settle_carpet();
    if (!from_break_) now_.rock.position.z() += release_lift();
    evaluate_forces();
    now_.energy = energy_of(now_);
    const double relaxed = std::max(0.0, inherited - now_.normal.elastic_energy);
    now_.deformation_loss += deformation + now_.normal.dissipated + relaxed;
    report_loss(0.0, deformation + now_.normal.dissipated + relaxed);
    in_contact_ = !now_.normal.touches.empty();
    report_first_sample();
    return std::nullopt;
  }

  // A fragment at its break (docs/rockfall-full.md, section 11.3): the elastic energy (J) of the
  // pistons it inherits, as the block left them. Pressed again by the fragment alone, a piston
  // under the crack may hold less (its axis now leaves the rock sooner, or a cut face is near):
  // what the pistons give up there is a deformation loss. Zero for a released rock.
  double inherited_elastic_energy() const {
    double energy = 0.0;
    for (const PistonTouch& touch : now_.normal.touches) {
      const Piston& piston = carpet_.at(touch.i, touch.j);
      energy += stored_energy(piston.cycle, piston.state) * piston.area;
    }
    return energy;
  }

  // As fast mode puts a release's contact point below the ground onto it (docs/rockfall-fast.md,
  // section 6): the smallest vertical lift (m) after which no piston's rest top lies inside the
  // rock, by bisection to kReleaseTolerance. Zero for a rock released clear of the ground.
  double release_lift() const {
    const Eigen::Matrix3d to_body = now_.rock.orientation.toRotationMatrix().transpose();
    double highest = -kInfinity;  // m: the highest rest top above the centre
    for (const Piston* piston : range_.pistons) highest = std::max(highest, piston->rest_top.z());
    highest -= now_.rock.position.z();
    const auto buried = [&](double lift) {
      const Eigen::Vector3d centre = now_.rock.position + Eigen::Vector3d(0.0, 0.0, lift);
      for (const Piston* piston : range_.pistons) {
        if (body_.value(to_body * (piston->rest_top - centre)) < 0.0) return true;
      }
      return false;
    };
    if (!buried(0.0)) return 0.0;
    double low = 0.0;
    double high = highest + body_.bounding_radius();
    while (high - low > kReleaseTolerance) {
      const double middle = 0.5 * (low + high);
      (buried(middle) ? low : high) = middle;
    }
    return high;
  }

  // One accepted step (paper 3.1, 3.3), with the guard's retries, the samples, losses and stops.
  std::optional<StopReason> advance() {
    if (now_.time >= parameters_.max_time) return StopReason::max_time;
    double dt = choose_step();
    const Eigen::Vector3d half_velocity = now_.rock.velocity + (0.5 * dt / body_.mass()) * explicit_force(now_);
    if (unsampled_ && travelled_ + half_velocity.norm() * dt > parameters_.sample_spacing) report_sample();
    const double friction_before = now_.friction_loss;
    const double deformation_before = now_.deformation_loss;
    for (int retry = 0;; ++retry) {
      if (dt < min_step() || !(now_.time + dt > now_.time)) {
        return recover(dt, "the step collapsed below its floor");
      }
      const Attempt attempt = step(dt);
      if (attempt == Attempt::accepted) break;
      const Eigen::Vector3d reached = now_.rock.position;
      restore();
      if (attempt == Attempt::outside) return outside(reached);
      if (!parameters_.guard) return recover(dt, "the state is not finite");
      if (retry >= parameters_.max_retries) return recover(dt, "blow-up not recovered by smaller steps");
      dt *= 0.5;
    }
    now_.last_step = dt;
    const double fresh = fresh_contact_step();  // s, infinite without ground under the rock
    // After a restart the contact's own steps are step_scale_ shorter, and so is the stall limit.
    stalled_steps_ = std::isfinite(fresh) && dt < kStallFraction * step_scale_ * fresh ? stalled_steps_ + 1 : 0;
    if (stalled_steps_ >= kStallSteps) return recover(dt, "the step stalled far below the contact's");
    travelled_ += (now_.rock.position - saved_.rock.position).norm();
    unsampled_ = true;
    report_loss(now_.friction_loss - friction_before, now_.deformation_loss - deformation_before);
    const bool in_contact = !now_.normal.touches.empty();
    if (in_contact != in_contact_) report_sample();
    in_contact_ = in_contact;
    if (!block_.bonds().empty() && break_up()) return std::nullopt;
    if (at_rest(dt)) return StopReason::at_rest;
    if (++steps_since_checkpoint_ >= kCheckpointSteps) checkpoint();
    return std::nullopt;
  }

  // --- recovery (docs/rockfall-full.md, section 5, "Recovery") ---------------------------------

  // Everything an accepted step changes: a sound state the rock can restart from.
  struct Checkpoint {
    RunState now;
    PistonCarpet carpet;
    std::vector<PistonTouch> previous_touches;
    bool in_contact, unsampled;
    long stalled_steps;
    double travelled, rest_window, centre_path, rim_path;
  };
  Checkpoint sound_state() const {
    return {now_,        carpet_,    previous_touches_, in_contact_,  unsampled_,
            stalled_steps_, travelled_, rest_window_,      centre_path_, rim_path_};
  }

  // After kCheckpointSteps accepted steps: the reports before the older checkpoint can no longer
  // be withdrawn and go to the observer; the newer checkpoint becomes the older.
  void checkpoint() {
    held_before_.pass_to(observer_);
    std::swap(held_before_, held_);
    older_ = std::move(newer_);
    newer_.emplace(sound_state());
    steps_since_checkpoint_ = 0;
  }

  // A step failed (`reason`, the shortest step tried `dt` s): the rock restarts from the older
  // checkpoint with the contact steps' rules scaled by kRestartStepScale once more and every
  // piston's compression bounded by its rest top's depth in the rock (section 3.5, which makes it
  // continuous where a piston axis grazes the rock), and every report since that checkpoint is
  // withdrawn; after parameters_.restarts restarts, or with the guard off, the failure is thrown
  // (StepFailure). Pistons that hold less under the bound give their elastic energy up as a
  // deformation loss.
  std::optional<StopReason> recover(double dt, const char* reason) {
    if (restarts_ >= parameters_.restarts || !parameters_.guard) {
      throw_numerical_failure(now_.time, now_.rock.position, dt, reason);
    }
    ++restarts_;
    observer_.on_restart(now_.time);
    Checkpoint& from = older_ ? *older_ : *newer_;
    now_ = from.now;
    carpet_ = from.carpet;
    previous_touches_ = from.previous_touches;
    in_contact_ = from.in_contact;
    unsampled_ = from.unsampled;
    stalled_steps_ = from.stalled_steps;
    travelled_ = from.travelled;
    rest_window_ = from.rest_window;
    centre_path_ = from.centre_path;
    rim_path_ = from.rim_path;
    range_.gather(carpet_, now_.range);
    contact_.bound_every_compression = true;
    const double elastic = now_.normal.elastic_energy;
    journal_.clear();
    evaluate_forces();
    now_.energy = energy_of(now_);
    const double relaxed = std::max(0.0, elastic - now_.normal.elastic_energy);
    now_.deformation_loss += now_.normal.dissipated + relaxed;
    if (older_) newer_ = std::move(older_);
    older_.reset();
    held_before_.withdraw();
    held_.withdraw();
    report_loss(0.0, now_.normal.dissipated + relaxed);
    steps_since_checkpoint_ = 0;
    step_scale_ *= kRestartStepScale;
    return std::nullopt;
  }

  // --- fracture (paper fig. 4) --------------------------------------------------------------

  // After an accepted step: the bonds' forces from the forces that end the step (those of its
  // second half kick: pistons, Coulomb friction, rolling resistance, drag, vegetation, gravity).
  // When one exceeds its strength, the block's state at the break is sampled and split; each
  // fragment gets a copy of the carpet in which the pistons the other fragments load are back at
  // their footprints (their elastic energy goes with the fragment that loads them), and the touches
  // it loads. Touches belong to the part that holds their contact point (RigidRock::part_at).
  bool break_up() {
    const std::vector<PistonTouch>& touches = now_.normal.touches;
    BodyLoads loads;
    loads.torque = now_.normal.torque + now_.drag_torque + kick_friction_torque_;
    for (std::size_t i = 0; i < touches.size(); ++i) {
      loads.contacts.push_back({touches[i].arm, touches[i].load * touches[i].normal + kick_friction_forces_[i]});
    }
    const std::vector<Eigen::Vector3d> forces = bond_forces(block_, now_.rock, loads);
    std::vector<bool> broken(forces.size(), false);
    bool any = false;
    for (std::size_t b = 0; b < forces.size(); ++b) {
      broken[b] = forces[b].norm() > block_.bonds()[b].strength;
      any = any || broken[b];
    }
    if (!any) return false;
    if (unsampled_) report_sample();
    std::vector<Fragment> pieces = split(block_, now_.rock, broken);
    std::vector<std::size_t> piece_of_part(body_.parts().size(), 0);
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      for (std::size_t part : pieces[k].parts) piece_of_part[part] = k;
    }
    const Eigen::Matrix3d to_body = now_.rock.orientation.toRotationMatrix().transpose();
    std::vector<std::size_t> piece_of_touch;
    for (const PistonTouch& touch : touches) piece_of_touch.push_back(piece_of_part[body_.part_at(to_body * touch.arm)]);
    for (std::size_t k = 0; k < pieces.size(); ++k) {
      RunStart start{std::move(pieces[k].block), pieces[k].state, now_.time, spacing_, carpet_, {}, k > 0};
      for (std::size_t i = 0; i < touches.size(); ++i) {
        if (piece_of_touch[i] == k) {
          start.touches.push_back(touches[i]);
          continue;
        }
        Piston& piston = start.carpet->at(touches[i].i, touches[i].j);
        press(piston.cycle, piston.state, piston.cycle.residual_compression(piston.state.max_compression));
      }
      fragments_.push_back(std::move(start));
    }
    return true;
  }

  // Paper 3.1, one kick-drift-kick step of `dt` seconds, forces at positions: half a kick with
  // the forces at the start, the drift, the carpet scrolled and pressed at the new position,
  // vegetation and drag with the half-step velocities, half a kick with the new forces.
  Attempt step(double dt) {
    saved_ = now_;
    journal_.clear();
    window_moved_ = false;
    half_kick(0.5 * dt);
    drift(body_, now_.rock, dt);
    now_.time += dt;
    const Eigen::Vector3d& x = now_.rock.position;
    if (!now_.rock.position.allFinite() || !now_.rock.orientation.coeffs().allFinite()) return Attempt::unsound;
    if (!ground_.contains(x.x(), x.y())) return Attempt::outside;
    now_.deformation_loss += settle_carpet();
    evaluate_forces();
    now_.deformation_loss += now_.normal.dissipated;
    half_kick(0.5 * dt);
    now_.energy = energy_of(now_);
    if (!parameters_.guard) return now_.rock.velocity.allFinite() ? Attempt::accepted : Attempt::unsound;
    const double floor = body_.mass() * parameters_.gravity * spacing_;
    return step_is_sound(now_.rock, saved_.energy, now_.energy, parameters_.guard_tolerance, floor)
               ? Attempt::accepted
               : Attempt::unsound;
  }

  // Undoes the last step: the run's state by copy; the carpet back to its window, the pistons
  // the step dropped with their states, and the journal of piston states in reverse.
  void restore() {
    now_ = saved_;
    if (window_moved_) {
      cover(saved_window_);
      for (const PistonChange& dropped : dropped_) carpet_.at(dropped.i, dropped.j).state = dropped.before;
    }
    for (auto change = journal_.rbegin(); change != journal_.rend(); ++change) {
      if (holds(carpet_.window(), change->i, change->j)) carpet_.at(change->i, change->j).state = change->before;
    }
    range_.gather(carpet_, now_.range);
  }

  // --- forces and energies ------------------------------------------------------------------

  // Paper 2.2: the carpet covers the vertical projection of the rock's bounding box plus one
  // spacing (and carpet_margin); the contact tests the pistons under the box plus one spacing.
  // Pistons the move drops are remembered for restore(). Returns the elastic energy of dropped
  // pistons (J), a deformation loss.
  double settle_carpet() {
    const Eigen::Vector3d& x = now_.rock.position;
    const Eigen::AlignedBox3d box = body_.world_bounds(now_.rock.orientation);
    const double s = spacing_;
    const auto first = [s](double low) { return static_cast<std::int64_t>(std::ceil(low / s)); };
    const auto end = [s](double high) { return static_cast<std::int64_t>(std::floor(high / s)) + 1; };
    const CarpetWindow range{first(x.x() + box.min().x() - s), end(x.x() + box.max().x() + s),
                             first(x.y() + box.min().y() - s), end(x.y() + box.max().y() + s)};
    const CarpetWindow window = widened(range, margin_cells_);
    double dropped = 0.0;
    window_moved_ = !same_window(window, carpet_.window());
    if (window_moved_) {
      saved_window_ = carpet_.window();
      dropped_.clear();
      for (const Piston& piston : carpet_.pistons()) {
        if (piston.state.max_compression > 0.0 && !holds(window, piston.i, piston.j)) {
          dropped_.push_back({piston.i, piston.j, piston.state});
        }
      }
      dropped = cover(window);
    }
    if (window_moved_ || !same_window(range, now_.range)) {
      now_.range = range;
      range_.gather(carpet_, range);
      now_.relief = relief_of(range_);
    }
    return dropped;
  }

  // Covers exactly the lattice points of `window`: region bounds half a spacing outside them, so
  // that no rounding adds or loses a row. Returns the dropped pistons' elastic energy (J).
  double cover(const CarpetWindow& window) {
    const double s = spacing_;
    const auto at = [s](std::int64_t k) { return (static_cast<double>(k) - 0.5) * s; };
    return carpet_.cover(at(window.i_begin), at(window.i_end), at(window.j_begin), at(window.j_end));
  }

  // Paper 3.3 steps 1-3 and paper 3.2 at the current position, with the current velocities: the
  // pistons are pressed unless the rock's bounding sphere is clear of every piston top; the
  // vegetation (step 4) and the drag take the current velocity. Coulomb friction is solved in
  // each kick (half_kick).
  void evaluate_forces() {
    std::swap(previous_touches_, now_.normal.touches);
    const bool clear = !now_.relief.has_ground || now_.relief.depth(now_.rock.position) > body_.bounding_radius();
    press_carpet(carpet_, clear ? empty_range_ : range_, body_, now_.rock.position,
                 now_.rock.orientation.toRotationMatrix(), contact_, previous_touches_, now_.normal, journal_);
    now_.vegetation = vegetation_force(now_.normal.touches, now_.rock.velocity, body_.mass());
    now_.drag_force = Eigen::Vector3d::Zero();
    now_.drag_torque = Eigen::Vector3d::Zero();
    if (parameters_.drag_coefficient > 0.0) {
      now_.drag_force = body_.drag(now_.rock.orientation, now_.rock.velocity, parameters_.air_density,
                                   parameters_.drag_coefficient, now_.drag_torque);
    }
  }

  // Every force but Coulomb friction (N): the pistons' responses, the vegetation, the drag and
  // gravity.
  Eigen::Vector3d explicit_force(const RunState& state) const {
    return state.normal.force + state.vegetation + state.drag_force +
           Eigen::Vector3d(0.0, 0.0, -parameters_.gravity * body_.mass());
  }

  // Half of a kick (paper 3.1, Newton and Euler) over `duration` seconds: the forces of the last
  // evaluation, then the Coulomb friction's implicit impulse from the velocities they leave. The
  // work of each force over a kick is exactly its impulse times the mean of the velocities before
  // and after (and its angular impulse times the mean spin), which books friction and drag losses
  // exactly.
  void half_kick(double duration) {
    RockState& rock = now_.rock;
    const Eigen::Vector3d v_before = rock.velocity;
    const Eigen::Vector3d w_before = angular_velocity(body_, rock);
    kick(rock, body_.mass(), explicit_force(now_), now_.normal.torque + now_.drag_torque, duration);
    FrictionImpulse friction;
    const bool bonded = !block_.bonds().empty();
    if (bonded) kick_friction_forces_.clear();
    if (!now_.normal.touches.empty()) {
      const Eigen::Matrix3d rotation = rock.orientation.toRotationMatrix();
      const Eigen::Matrix3d world_inertia = rotation * body_.inertia() * rotation.transpose();
      friction = friction_impulse(now_.normal.touches, rock.velocity, angular_velocity(body_, rock), body_.mass(),
                                  world_inertia, parameters_.friction_slip_speed, parameters_.rolling_resistance,
                                  duration, bonded ? &kick_friction_forces_ : nullptr);
      rock.velocity += friction.linear / body_.mass();
      rock.angular_momentum += friction.angular;
    }
    if (bonded) kick_friction_torque_ = friction.angular / duration;
    const Eigen::Vector3d v_mean = 0.5 * (v_before + rock.velocity);
    const Eigen::Vector3d w_mean = 0.5 * (w_before + angular_velocity(body_, rock));
    now_.friction_loss -= friction.linear.dot(v_mean) + friction.angular.dot(w_mean) +
                          duration * now_.vegetation.dot(v_mean);
    now_.drag_loss -= duration * (now_.drag_force.dot(v_mean) + now_.drag_torque.dot(w_mean));
  }

  StepEnergy energy_of(const RunState& state) const {
    StepEnergy energy;
    energy.kinetic = kinetic_energy(body_, state.rock);
    energy.potential = body_.mass() * parameters_.gravity * state.rock.position.z();
    energy.elastic = state.normal.elastic_energy;
    return energy;
  }

  // --- time steps ---------------------------------------------------------------------------

  // Issue 4, Deliver 5: the step (s). Free flight takes max_flight_step (at most twice the last
  // step, within max_time and half a sample spacing of path). Where the rock can reach the
  // pistons within it: the stiffness of a fresh contact; the stiffness of the loaded pistons
  // (translation and rotation); and the approach rule: the rock's material at each piston top
  // moves along the piston's axis by at most approach_fraction spacings beyond the top's gap to
  // the rock (loaded pistons: gap 0), in either direction, so that contacts start and end alike.
  double choose_step() const {
    const RockState& rock = now_.rock;
    const double speed = rock.velocity.norm();
    double dt = std::min({parameters_.max_flight_step, 2.0 * now_.last_step, parameters_.max_time - now_.time});
    if (speed > 0.0) dt = std::min(dt, 0.5 * parameters_.sample_spacing / speed);
    const CarpetRelief& relief = now_.relief;
    if (!relief.has_ground) return dt;
    const Eigen::Vector3d& n = relief.normal;
    const Eigen::Vector3d w = angular_velocity(body_, rock);
    const double radius = body_.bounding_radius();
    const double normal_speed = rock.velocity.dot(n);
    // Bound of the speed (m/s) at which the rock can close on the range's tops along n.
    const double closing = std::max(0.0, -normal_speed) + w.norm() * radius +
                           (rock.velocity - normal_speed * n).norm() * relief.tilt;
    const double clearance = relief.depth(rock.position) - radius;  // m, > 0: no top inside the bounding sphere
    const bool touching = !now_.normal.touches.empty();
    if (!touching && clearance > closing * dt + 0.5 * parameters_.gravity * dt * dt) return dt;

    dt = std::min(dt, step_scale_ * fresh_contact_step());
    const double period_factor = step_scale_ * parameters_.time_step_factor * 2.0 * std::numbers::pi;
    if (now_.normal.stiffness > 0.0) dt = std::min(dt, period_factor * std::sqrt(body_.mass() / now_.normal.stiffness));
    if (now_.normal.rotational_stiffness > 0.0) {
      dt = std::min(dt, period_factor * std::sqrt(body_.min_inertia() / now_.normal.rotational_stiffness));
    }
    const double allowance = step_scale_ * parameters_.approach_fraction * spacing_;  // m per step
    if (clearance > 0.0 && closing > 0.0) dt = std::min(dt, (clearance + allowance) / closing);
    const auto limit = [&](const Eigen::Vector3d& arm, const Eigen::Vector3d& axis, double gap) {
      const double along = std::abs((rock.velocity + w.cross(arm)).dot(axis));
      if (along * dt > gap + allowance) dt = (gap + allowance) / along;
    };
    for (const NearPiston& piston : now_.normal.near) limit(piston.arm, piston.axis, piston.gap);
    for (const PistonTouch& touch : now_.normal.touches) limit(touch.arm, touch.normal, 0.0);
    return dt;
  }

  // The step's floor (s): kMinStepFraction of a fresh contact's step; none where the range has no
  // ground (the clock's resolution then).
  double min_step() const {
    const double fresh = fresh_contact_step();
    return std::isfinite(fresh) ? kMinStepFraction * fresh : 0.0;
  }

  // Issue 4, Deliver 5, the coming contact: factor x 2 pi sqrt(m / K) with K = k3 times the
  // area of fresh_contact_pistons pistons (s), k3 the stiffest under the rock.
  double fresh_contact_step() const {
    const double stiffness = now_.relief.stiffest * parameters_.fresh_contact_pistons * spacing_ * spacing_;
    if (!(stiffness > 0.0)) return kInfinity;
    return parameters_.time_step_factor * 2.0 * std::numbers::pi * std::sqrt(body_.mass() / stiffness);
  }

  // --- stops, samples, losses ---------------------------------------------------------------

  // Stop rule at rest, after a step of `dt` seconds: over windows of stop_duration, the mean
  // speed of the centre and of the rim (|w| x bounding radius) stayed below stop_speed, and the
  // rock is in contact at the window's end. The mean, not the instantaneous speed, because on the
  // unloading/reloading line of paper fig. 2 a resting rock keeps an undamped vertical
  // oscillation and its contact may flicker (docs/rockfall-full.md, section 6).
  bool at_rest(double dt) {
    rest_window_ += dt;
    centre_path_ += now_.rock.velocity.norm() * dt;
    rim_path_ += angular_velocity(body_, now_.rock).norm() * body_.bounding_radius() * dt;
    if (rest_window_ < parameters_.stop_duration) return false;
    const double allowed = parameters_.stop_speed * rest_window_;
    const bool resting = in_contact_ && centre_path_ < allowed && rim_path_ < allowed;
    rest_window_ = centre_path_ = rim_path_ = 0.0;
    return resting;
  }

  StopReason outside(const Eigen::Vector3d& at) const { return reason_for_leaving(ground_.model().spec(), at); }

  TrajectorySample sample() const {
    const Eigen::Vector3d& x = now_.rock.position;
    const bool on_ground = x.allFinite() && ground_.contains(x.x(), x.y());
    return {now_.time, x, now_.rock.velocity, now_.energy.kinetic,
            on_ground ? x.z() - ground_.height(x.x(), x.y()) : 0.0};
  }
  void report_sample() {
    held_.sample(sample());
    travelled_ = 0.0;
    unsampled_ = false;
  }
  // A new fragment's first sample goes to on_fragment (trajectory_observer.hpp).
  void report_first_sample() {
    if (announced_) {
      held_.fragment(sample());
      travelled_ = 0.0;
      unsampled_ = false;
    } else {
      report_sample();
    }
  }
  // Losses at the load-weighted contact point (the centre when nothing touches).
  void report_loss(double friction, double deformation) {
    if (friction == 0.0 && deformation == 0.0) return;
    const Eigen::Vector3d at = now_.rock.position + now_.normal.centroid();
    held_.loss(at.x(), at.y(), friction, deformation);
  }

  const FullModelParameters& parameters_;
  const PerturbedGround& ground_;
  TrajectoryObserver& observer_;
  const FracturedBody block_;
  const RigidRock& body_;            // block_'s
  const double spacing_;             // m: carpet_spacing x the released rock's nominal equivalent diameter cbrt(6 V / pi)
  const std::int64_t margin_cells_;  // lattice steps of carpet_margin
  PistonContactParameters contact_;  // bound_every_compression after a restart
  PistonCarpet carpet_;
  PistonRange range_;                   // pistons of now_.range
  const PistonRange empty_range_;       // tests nothing (the rock is clear of the carpet)
  bool window_moved_ = false;           // the last step moved the carpet's window...
  CarpetWindow saved_window_;           // ...from this one...
  std::vector<PistonChange> dropped_;   // ...dropping these pressed pistons
  std::vector<PistonChange> journal_;   // piston states the last step changed
  std::vector<PistonTouch> previous_touches_;
  RunState now_, saved_;
  bool from_break_ = false;          // a fragment, starting at the break that made it
  bool announced_ = false;           // ...reported through on_fragment
  std::vector<RunStart> fragments_;  // after a break
  std::vector<Eigen::Vector3d> kick_friction_forces_;  // N per touch, Coulomb friction of the last half kick (bonded bodies)
  Eigen::Vector3d kick_friction_torque_ = Eigen::Vector3d::Zero();  // N m, its torque with rolling resistance
  bool in_contact_ = false;
  long stalled_steps_ = 0;           // accepted steps in a row shorter than kStallFraction of a fresh contact's
  double travelled_ = 0.0;           // m of path since the last sample
  bool unsampled_ = false;
  double rest_window_ = 0.0;         // s of the current rest window
  double centre_path_ = 0.0;         // m travelled by the centre in it
  double rim_path_ = 0.0;            // m travelled by the rim in it
  // The recovery: reports since the older checkpoint (held_before_, up to the newer one, and held_),
  // the last two checkpoints, restarts so far and the scale of the contact steps' rules.
  HeldReports held_before_, held_;
  std::optional<Checkpoint> older_, newer_;
  long steps_since_checkpoint_ = 0;
  int restarts_ = 0;
  double step_scale_ = 1.0;
};

}  // namespace

StopReason FullModel::run(const PerturbedGround& ground, const Rock& rock, RigidBodyState start,
                          TrajectoryObserver& observer) const {
  EnergyBalance balance;
  return run(ground, rock, start, observer, balance);
}

// Paper 3.1-3.3 and fig. 4: one trajectory from `start` to its stop, with its energy bookkeeping:
// the block (pre_fractured_block, one part when intact), then every fragment of its breaks.
StopReason FullModel::run(const PerturbedGround& ground, const Rock& rock, RigidBodyState start,
                          TrajectoryObserver& observer, EnergyBalance& balance) const {
  FracturedBody block = pre_fractured_block(rock, parameters_.fracture_parts, parameters_.fracture_strength,
                                            parameters_.surface_samples, parameters_.mass_resolution);
  const RockState released =
      rock_state(block.body(), start.position, start.velocity, start.orientation, start.angular_velocity);
  const double spacing = parameters_.carpet_spacing * std::cbrt(6.0 * rock.volume() / std::numbers::pi);
  balance = EnergyBalance{};
  // Runs in order: the continuing fragment of a break first, the others after every earlier one.
  std::deque<RunStart> runs;
  runs.push_back({std::move(block), released, 0.0, spacing, std::nullopt, {}, false});
  std::optional<StopReason> first_stop;
  while (!runs.empty()) {
    RunStart next = std::move(runs.front());
    runs.pop_front();
    RunEnd end = FullModelRun(parameters_, ground, observer, std::move(next)).run(balance);
    if (end.stop) {
      if (!first_stop) first_stop = end.stop;
      continue;
    }
    for (std::size_t k = 1; k < end.fragments.size(); ++k) runs.push_back(std::move(end.fragments[k]));
    runs.push_front(std::move(end.fragments.front()));
  }
  return *first_stop;
}

}  // namespace talus
