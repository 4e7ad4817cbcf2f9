// The mud-flow run (paper 4; docs/mudflow.md): release, then coarse steps of block time
// stepping (paper 4.2) with kick-drift-kick leapfrog, each coarse step checked by the guard,
// adaptivity between coarse steps, entrainment, deposition, maps and snapshots.
#include "talus/mudflow/mudflow_simulation.hpp"

#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>

#include "talus/core/errors.hpp"
#include "talus/mudflow/entrainment.hpp"
#include "talus/mudflow/evaluation_order.hpp"
#include "talus/mudflow/flow_density.hpp"
#include "talus/mudflow/flow_forces.hpp"
#include "talus/mudflow/flow_guard.hpp"
#include "talus/mudflow/parallel_loop_choice.hpp"
#include "talus/mudflow/pair_search.hpp"
#include "talus/mudflow/particle_fission.hpp"
#include "talus/mudflow/particle_fusion.hpp"
#include "talus/mudflow/particle_parts.hpp"
#include "talus/mudflow/release_particles.hpp"
#include "talus/mudflow/run_end_estimate.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"
#include "talus/mudflow/surface_following.hpp"
#include "talus/mudflow/time_levels.hpp"

namespace talus {

double cells_crossed_per_step(const MudflowSettings& settings) {
  if (settings.cells_per_step > 0) return settings.cells_per_step;
  return settings.adaptive && settings.crowded_merge > 0 ? 1.0 : 0.5;
}

const char* to_string(MudflowEnd end) {
  switch (end) {
    case MudflowEnd::duration:
      return "duration";
    case MudflowEnd::energy:
      return "energy";
    case MudflowEnd::outflow:
      return "outflow";
  }
  return "unknown";
}

namespace {

// Times within this fraction of a coarse step count as equal (map and snapshot schedules).
constexpr double kTimeSlack = 1e-9;
// Limits on the settings that keep the tick clock (2^(deepest_level + max_retries) ticks per
// coarse step) inside 64 bits with room to spare.
constexpr int kMostLevels = 24;
constexpr int kMostRetries = 12;
constexpr int kMostCoarseLevels = 8;

void require(bool condition, const std::string& what) {
  if (!condition) throw InputError("mudflow: " + what);
}

void validate(const MudflowSettings& s) {
  require(std::isfinite(s.duration) && s.duration > 0, "the duration must be a positive number of seconds");
  require(s.stop_energy_fraction >= 0 && s.stop_energy_fraction < 1, "the stop energy fraction must lie in [0, 1)");
  require(s.threads >= 0, "the thread count must be 0 (all cores) or positive");
  require(s.parallel_particles >= 1, "the parallel particle count must be 1 or more");
  require(s.interleaved_particles >= 1, "the interleaved particle count must be 1 or more");
  require(s.parallel_check_period == 0 || s.parallel_check_period >= 3,
          "the parallel check period must be 0 (always parallel) or at least 3 coarse steps");
  require(std::isfinite(s.mud_density) && s.mud_density > 0, "the mud density must be positive (kg/m3)");
  require(std::isfinite(s.gravity) && s.gravity > 0, "gravity must be positive (m/s2)");
  require(std::isfinite(s.particle_size) && s.particle_size > 0, "the particle size must be positive (m)");
  require(s.coarse_levels >= 0 && s.coarse_levels <= kMostCoarseLevels,
          "coarse levels must lie in [0, " + std::to_string(kMostCoarseLevels) + "]");
  require(s.split_threshold > 0, "the split threshold must be positive");
  require(s.merge_threshold >= 0 && s.merge_speed >= 0, "the merge threshold and speed must not be negative");
  require(s.courant > 0 && s.courant <= 1, "the Courant number must lie in (0, 1]");
  require(s.cells_per_step >= 0 && s.cells_per_step <= 10, "the cells crossed per step must lie in (0, 10] or be 0 (automatic)");
  require(std::isfinite(s.longest_step) && s.longest_step > 0, "the longest step must be positive (s)");
  require(s.deepest_level >= 0 && s.deepest_level <= kMostLevels,
          "the deepest level must lie in [0, " + std::to_string(kMostLevels) + "]");
  require(s.max_retries >= 0 && s.max_retries <= kMostRetries,
          "max retries must lie in [0, " + std::to_string(kMostRetries) + "]");
  require(std::isfinite(s.unguarded_step) && s.unguarded_step >= 0, "the forced step must not be negative (s)");
  require(std::isfinite(s.curvature_span) && s.curvature_span >= 0, "the curvature span must not be negative (m)");
  const RheologyParameters& r = s.rheology;
  require(std::isfinite(r.friction) && r.friction >= 0 && r.friction <= 1, "the friction coefficient must lie in [0, 1]");
  require(r.turbulence > 0, "the Voellmy turbulence xi must be positive (m/s2)");
  require(r.viscosity >= 0 && r.yield_stress >= 0, "viscosity and yield stress must not be negative");
  require(r.internal_viscosity >= 0, "the internal viscosity must not be negative (m2/s)");
  require(s.stop_speed >= 0 && s.stop_duration >= 0, "the stop speed and duration must not be negative");
  require(s.entrainment_rate >= 0, "the entrainment rate must not be negative (1/m)");
  require(s.arrival_depth >= 0, "the arrival depth must not be negative (m)");
  require(std::isfinite(s.map_interval) && s.map_interval > 0, "the map interval must be positive (s)");
  require(std::isfinite(s.snapshot_interval) && s.snapshot_interval >= 0, "the snapshot interval must not be negative (s)");
}

// A progress line's phase while the flow runs: simulated time, expected end and wall time left
// (run_end_estimate.hpp), e.g. "mud flow: simulated 88.5 s of about 140 s, about 12 s left".
std::string progress_phase(const RunEndEstimate& estimate) {
  const double left = estimate.wall_seconds_left();
  char text[128];
  std::snprintf(text, sizeof text, "mud flow: simulated %.1f s of about %.0f s, about %.*f s left", estimate.time(),
                estimate.expected_end(), left < 10.0 ? 1 : 0, left);
  return text;
}

// Paper 4.2: the step of each level 0..finest_level, coarse_step / 2^level (s).
std::vector<double> level_steps(double coarse_step, int finest_level) {
  std::vector<double> steps;
  for (int level = 0; level <= finest_level; ++level) steps.push_back(std::ldexp(coarse_step, -level));
  return steps;
}

// Sets OpenMP's default thread count for the calling thread and puts the previous one back.
class ThreadCount {
 public:
  explicit ThreadCount(int threads) : previous_(omp_get_max_threads()) { omp_set_num_threads(threads); }
  ~ThreadCount() { omp_set_num_threads(previous_); }
  ThreadCount(const ThreadCount&) = delete;
  ThreadCount& operator=(const ThreadCount&) = delete;

 private:
  int previous_;
};

class MudflowRun {
 public:
  MudflowRun(const GroundModel& ground, const ReleaseSet& release, const Grid<float>* erodible,
             const MudflowSettings& settings, Progress* progress)
      : ground_(ground),
        s_(settings),
        progress_(progress),
        threads_(settings.threads > 0 ? settings.threads : omp_get_max_threads()),
        coarse_step_(settings.unguarded_step > 0 ? settings.unguarded_step : settings.longest_step),
        finest_level_(settings.deepest_level + settings.max_retries),
        level_steps_(level_steps(coarse_step_, finest_level_)),
        column_{settings.mud_density, settings.gravity},
        forces_{settings.mud_density, settings.gravity, settings.rheology.internal_viscosity, settings.pressure,
                settings.rheology.lateral_mixing > 0.0},
        criteria_{settings.courant, settings.rheology.internal_viscosity,
                  std::min(ground.spec().cell_width(), ground.spec().cell_height()), cells_crossed_per_step(settings)},
        largest_cell_(std::max(ground.spec().cell_width(), ground.spec().cell_height())),
        smallest_smoothing_(settings.adaptive && settings.crowded_merge > 0
                                ? settings.particle_size * kSupportPerSpacing
                                : std::numeric_limits<double>::infinity()),
        maps_(ground, settings.mud_density, settings.arrival_depth, erodible != nullptr, smallest_smoothing_),
        loops_(settings.parallel_check_period) {
    ReleaseLayout layout;
    layout.spacing = settings.particle_size * (settings.adaptive ? std::ldexp(1.0, settings.coarse_levels) : 1.0);
    layout.mud_density = settings.mud_density;
    layout.seed = settings.seed;
    layout.thickness = settings.release_thickness;
    p_ = release_particles(ground, release, layout);
    if (settings.node_normals) node_slopes_.emplace(ground);
    if (erodible != nullptr) {
      require_same_grid(ground.spec(), erodible->spec(), "mudflow: DEM and erodible depth");
      entrainment_.emplace(ground, *erodible, settings.entrainment_rate, settings.mud_density);
      eroded_ = Grid<float>(ground.spec(), 0.0f);
    }
  }

  MudflowResult run();

 private:
  // Per-particle loops, in parallel; each call of f writes only its own particle's slots.
  template <class F>
  void for_each_listed(const std::vector<std::uint32_t>& list, F&& f) const {
    const long count = static_cast<long>(list.size());
    if (threads_for(list.size()) == 1) {
      for (const std::uint32_t i : list) f(static_cast<std::size_t>(i));
      return;
    }
#pragma omp parallel for num_threads(threads_) schedule(static)
    for (long k = 0; k < count; ++k) f(static_cast<std::size_t>(list[static_cast<std::size_t>(k)]));
  }

  // Threads for a loop over `count` particles. Short loops stay on one thread
  // (settings.parallel_particles): a parallel region costs microseconds on an idle machine and
  // milliseconds on a loaded one, when a spinning thread loses its core; so do all loops while
  // timed trials find one thread faster (loops_).
  int threads_for(std::size_t count) const {
    const bool parallel = threads_ > 1 && loops_.parallel() && count >= static_cast<std::size_t>(s_.parallel_particles);
    return parallel ? threads_ : 1;
  }
  // The pair search over every particle with the given radii, sorted on the threads of the loops
  // over `active` particles that will use it (one thread for a short substep's few particles).
  void rebuild_pairs(const std::vector<double>& radii, std::size_t active) {
    pairs_.rebuild(p_, radii, s_.particle_size * kSupportPerSpacing, threads_for(active));
  }

  double step_of(int level) const { return level_steps_[static_cast<std::size_t>(level)]; }
  bool flowing(std::size_t i) const { return p_.state[i] == ParticleState::flowing && outside_[i] == 0; }
  double time() const { return static_cast<double>(coarse_steps_) * coarse_step_; }

  void resize_work();
  void place_all_on_ground();
  void evaluate(const std::vector<std::uint32_t>& list);
  void update_density(std::size_t i);
  void update_forces(std::size_t i);
  void evaluate_all();
  int wanted_level(std::size_t i, double closing) const;
  void kick(std::size_t i, double duration);
  void close_steps(const std::vector<std::uint32_t>& list);
  void open_steps(const std::vector<std::uint32_t>& list, std::uint64_t tick);
  void entrain(const std::vector<std::uint32_t>& list);
  void drift(const std::vector<std::uint32_t>& list, double duration);
  void coarse_step();
  bool adapt();
  void compact_and_sort();
  void refresh();
  void reset_smoothing();
  void record(MudflowResult& result);
  void snapshot(MudflowResult& result) const;

  const GroundModel& ground_;
  const MudflowSettings& s_;
  Progress* progress_;
  const int threads_;
  const double coarse_step_;     // s: the level-0 step
  const int finest_level_;       // the clock has 2^finest_level_ ticks per coarse step
  const std::vector<double> level_steps_;  // s: the step of each level, coarse_step_ / 2^level
  const ColumnConstants column_;
  const FlowForceConstants forces_;
  const StepCriteria criteria_;
  const double largest_cell_;    // m: the DEM's larger cell side; the curvature spans at least one
  // m: the least smoothing radius (flow_density.hpp): the finest particles' support radius with
  // crowded fusion, else infinite (each particle's own support radius).
  const double smallest_smoothing_;

  ParticleSet p_;
  PairSearch pairs_;  // the sums' pairs, with the smoothing radii; the adaptivity's, with the support radii
  double reference_elevation_ = 0;  // m: lowest foot at the release (potential energy zero)
  FootNormals normals_;
  std::vector<NeighbourList> neighbours_;
  // Per thread, reused: evaluate_part_in_order's scratch and the forces left for after every density.
  std::vector<std::vector<NeighbourSpan>> spans_;
  std::vector<std::vector<std::uint32_t>> waiting_;
  std::vector<double> smoothing_;         // m: support radius R_s of the sums (flow_density.hpp)
  std::vector<BasalResistance> resistance_;
  std::vector<Eigen::Vector3d> departure_;  // m/s: u - u_mean in the tangent plane, at the latest evaluation
  std::vector<std::uint8_t> wanted_;      // level the criteria ask for (with the guard's depth)
  std::vector<std::uint64_t> next_sync_;  // tick at which the particle's step ends
  std::vector<char> outside_;             // left the valid area during this coarse step (2: the window's halo)
  std::vector<double> outflow_mass_;      // kg: its mass when it left
  std::vector<double> outflow_energy_;    // J: the energy it took with it (flow_guard.hpp)
  // Level of each particle as the limiter sees it: its level while it flows, -1 (ignored) once it
  // is deposited or has left; kept up to date during the coarse step (open_steps).
  std::vector<std::int8_t> limiter_level_;
  std::vector<char> erode_flags_;         // entrainment's selection, reused
  std::vector<double> mass_before_;       // kg: masses before an entrainment call, reused

  std::optional<Entrainment> entrainment_;
  std::optional<NodeSlopes> node_slopes_;  // with [contact] node_normals
  const NodeSlopes* node_slopes() const { return node_slopes_ ? &*node_slopes_ : nullptr; }
  Grid<float> eroded_;
  FlowMaps maps_;
  ParallelLoopChoice loops_;

  int depth_ = 0;                 // guard: every level is this much deeper
  std::uint64_t coarse_steps_ = 0;
  std::uint64_t particle_steps_ = 0;
  std::size_t guard_retries_ = 0;
  std::size_t splits_ = 0, merges_ = 0;
  double outflow_volume_ = 0, entrained_volume_ = 0;
  double halo_outflow_volume_ = 0;  // of outflow_volume_, across settings.window_edge
  double energy_source_ = 0;     // J brought by entrained mass minus taken by outflow, this coarse step
  double adaptivity_mass_change_ = 0, adaptivity_momentum_change_ = 0;
};

void MudflowRun::resize_work() {
  const std::size_t n = p_.size();
  normals_.resize(n);
  neighbours_.resize(n);
  smoothing_.resize(n);
  resistance_.resize(n);
  departure_.resize(n, Eigen::Vector3d::Zero());
  wanted_.resize(n, 0);
  next_sync_.resize(n, 0);
  outside_.assign(n, 0);
  outflow_mass_.assign(n, 0.0);
  outflow_energy_.assign(n, 0.0);
  limiter_level_.resize(n);
}

// After the particle set changed (adaptivity, a guard restore): work arrays to size, feet
// on the ground, and densities and forces of every particle.
void MudflowRun::refresh() {
  resize_work();
  place_all_on_ground();
  evaluate_all();
}

// Smoothing radii of every particle from its stored density, after the particles were reordered.
void MudflowRun::reset_smoothing() {
  for (std::size_t i = 0; i < p_.size(); ++i) smoothing_[i] = smoothing_radius(p_, i, smallest_smoothing_);
}

void MudflowRun::place_all_on_ground() {
  std::vector<std::uint32_t> all(p_.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = static_cast<std::uint32_t>(i);
  for_each_listed(all, [&](std::size_t i) {
    place_on_ground(ground_, p_, i, normals_, node_slopes());
    smoothing_[i] = smoothing_radius(p_, i, smallest_smoothing_);
  });
}

// Density of every listed particle, then the forces, basal resistance and wanted level of the
// flowing ones (paper 4.1). The sums read the pair search's copies of the positions, masses and
// smoothing radii of the latest densities; the forces read the neighbours' new densities. A long
// list is evaluated in the order of evaluation_order.hpp, each thread's forces following its
// densities while the neighbour lists are in the cache; a shorter one in two passes.
void MudflowRun::evaluate(const std::vector<std::uint32_t>& list) {
  rebuild_pairs(smoothing_, list.size());
  const int threads = threads_for(list.size());
  if (list.size() < static_cast<std::size_t>(s_.interleaved_particles) * static_cast<std::size_t>(threads)) {
    for_each_listed(list, [&](std::size_t i) { update_density(i); });
    for_each_listed(list, [&](std::size_t i) { update_forces(i); });
  } else {
    const auto density = [this](std::uint32_t i) {
      update_density(i);
      return neighbour_span(i, neighbours_[i]);
    };
    const auto forces = [this](std::uint32_t k) { update_forces(k); };
    const auto parts = static_cast<std::size_t>(threads);
    spans_.resize(parts);
    waiting_.resize(parts);
    for_each_part(list.size(), parts, [&](std::size_t part, std::size_t first, std::size_t last) {
      evaluate_part_in_order(list, first, last, density, forces, spans_[part], waiting_[part]);
    });
    for_each_part(parts, parts, [&](std::size_t part, std::size_t, std::size_t) {
      for (const std::uint32_t k : waiting_[part]) update_forces(k);
    });
  }
  for (const std::uint32_t i : list) {
    if (p_.state[i] == ParticleState::flowing) ++particle_steps_;
  }
}

// Paper 4.1: the areal density and column state of particle i and its smoothing radius for the
// next evaluation.
void MudflowRun::update_density(std::size_t i) {
  const double sigma = gather_density(p_, pairs_, i, smoothing_[i], neighbours_[i]);
  set_column_state(p_, i, sigma, normals_.z[i], column_);
  smoothing_[i] = smoothing_radius(p_, i, smallest_smoothing_);
}

// Paper 4.1: the forces on flowing particle i, its basal resistance and the level it wants.
void MudflowRun::update_forces(std::size_t i) {
  if (p_.state[i] != ParticleState::flowing) return;
  const double g = s_.gravity;
  const FlowAcceleration forces = flow_acceleration(p_, i, neighbours_[i], normals_, forces_);
  Eigen::Vector3d a = forces.acceleration;
  if (s_.step_normal) {
    // [contact] step_normal: gravity's pull along the ground on the normal averaged over the
    // step ahead (docs/mudflow.md section 6), the rest of the acceleration as it was.
    const Eigen::Vector3d foot = normals_.at(i);
    const Eigen::Vector3d across = step_averaged_normal(ground_, foot, p_.x[i], p_.y[i], p_.velocity(i),
                                                        step_of(p_.level[i]), node_slopes());
    const Eigen::Vector3d weight(0.0, 0.0, -g);
    a = tangent_part(a + tangent_part(weight, across) - tangent_part(weight, foot), foot);
  }
  p_.ax[i] = a.x();
  p_.ay[i] = a.y();
  p_.az[i] = a.z();
  if (forces_.mean_velocity) departure_[i] = tangent_part(p_.velocity(i) - forces.mean_velocity, normals_.at(i));
  const Eigen::Vector3d v = p_.velocity(i);
  const double speed = v.norm();
  const double cos_slope = normals_.z[i];
  double normal_acceleration = g * cos_slope;
  const NodeSquare square = ground_.locate(p_.x[i], p_.y[i]);
  if (s_.curvature && speed > 0.0) {
    const double spacing = p_.radius[i] / kSupportPerSpacing;
    const double half_span = 0.5 * std::max({s_.curvature_span, largest_cell_, spacing});
    const double kappa = curvature_along(ground_, p_.x[i], p_.y[i], v / speed, half_span, node_slopes());
    normal_acceleration = std::max(0.0, normal_acceleration + kappa * speed * speed);
  }
  BasalContact contact;
  contact.depth = p_.depth[i];
  contact.normal_acceleration = normal_acceleration;
  contact.vegetation_deperdition = ground_.material_field(&GroundMaterial::vegetation_deperdition, square);
  resistance_[i] = basal_resistance(s_.rheology, contact, s_.mud_density, g);
  wanted_[i] = static_cast<std::uint8_t>(wanted_level(i, forces.closing_speed));
}

void MudflowRun::evaluate_all() {
  std::vector<std::uint32_t> list;
  list.reserve(p_.size());
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (outside_[i] == 0) list.push_back(static_cast<std::uint32_t>(i));
  }
  evaluate(list);
}

// Paper 4.2: the level of the step the particle's size, the Courant condition (with `closing`,
// the speed at which its neighbours close in, m/s) and its acceleration allow, made deeper by the
// guard's retries.
int MudflowRun::wanted_level(std::size_t i, double closing) const {
  if (s_.unguarded_step > 0) return depth_;
  const double spacing = smoothing_[i] / kSupportPerSpacing;
  // The pressure's wave speed sqrt(dPi/dsigma): sqrt(g cos(theta) h) for the thin-layer pressure,
  // sqrt(g h / cos(theta)) for the vertical column's.
  const double cos_slope = normals_.z[i];
  const double wave_speed = s_.pressure == PressureColumn::normal ? std::sqrt(s_.gravity * cos_slope * p_.depth[i])
                                                                  : std::sqrt(s_.gravity * p_.depth[i] / cos_slope);
  const double acceleration = std::sqrt(p_.ax[i] * p_.ax[i] + p_.ay[i] * p_.ay[i] + p_.az[i] * p_.az[i]);
  const double step = stable_step(spacing, wave_speed, closing, p_.velocity(i).norm(), acceleration, criteria_);
  return level_for_step(step, coarse_step_, s_.deepest_level) + depth_;
}

// New steps for the flowing particles whose step ends at `tick`: their levels, then the opening
// half kick. One global level without adaptivity (the deepest any particle wants); with it, each
// particle's wanted level, limited against its flowing neighbours' (their new wanted level where
// they are also choosing, else their level).
void MudflowRun::open_steps(const std::vector<std::uint32_t>& list, std::uint64_t tick) {
  if (!s_.adaptive || s_.unguarded_step > 0) {
    int level = depth_;
    for (const std::uint32_t i : list) level = std::max(level, static_cast<int>(wanted_[i]));
    level = aligned_level(level, tick, finest_level_);
    for (const std::uint32_t i : list) p_.level[i] = static_cast<std::uint8_t>(level);
    for_each_listed(list, [&](std::size_t i) { kick(i, 0.5 * step_of(level)); });
    return;
  }
  // The particles choosing see each other's wanted levels, the others their current levels.
  for (const std::uint32_t i : list) limiter_level_[i] = static_cast<std::int8_t>(wanted_[i]);
  for_each_listed(list, [&](std::size_t i) {
    const int limited = limited_level(wanted_[i], neighbours_[i], [&](std::uint32_t j) { return limiter_level_[j]; });
    p_.level[i] = static_cast<std::uint8_t>(aligned_level(limited, tick, finest_level_));
    kick(i, 0.5 * step_of(p_.level[i]));
  });
  for (const std::uint32_t i : list) limiter_level_[i] = static_cast<std::int8_t>(p_.level[i]);
}

// Half a leapfrog kick (paper 4.1 forces): the conservative and viscous acceleration, then the
// basal resistance integrated implicitly over the same time, which can stop the particle but
// never reverse it.
void MudflowRun::kick(std::size_t i, double duration) {
  Eigen::Vector3d v = p_.velocity(i) + duration * Eigen::Vector3d(p_.ax[i], p_.ay[i], p_.az[i]);
  if (forces_.mean_velocity) {
    // Lateral mixing (docs/mudflow.md section 4): du/dt = -(C / s) |du| du, implicit over the
    // step of which this kick is half. The departure du is the one measured with the forces,
    // when all velocities were at one time, so that the mean's lag cannot brake a column that
    // accelerates with its neighbours.
    const Eigen::Vector3d& departure = departure_[i];
    const double side = smoothing_[i] / kSupportPerSpacing;  // sqrt(m / sigma) within the radius's bounds (m)
    const double c = s_.rheology.lateral_mixing * departure.norm() * 2.0 * duration / side;
    v -= 0.5 * c / (1.0 + c) * departure;
  }
  const double speed = v.norm();
  if (speed > 0.0) v *= resisted_speed(resistance_[i], speed, duration) / speed;
  p_.vx[i] = v.x();
  p_.vy[i] = v.y();
  p_.vz[i] = v.z();
}

// The closing half kick of the listed particles' steps, then deposition: a particle slower
// than stop_speed for stop_duration deposits where the bed holds it, i.e. where its driving
// acceleration is within the resistance the bed offers at the stop speed.
void MudflowRun::close_steps(const std::vector<std::uint32_t>& list) {
  for_each_listed(list, [&](std::size_t i) {
    if (p_.state[i] != ParticleState::flowing) return;
    const double step = step_of(p_.level[i]);
    kick(i, 0.5 * step);
    const double speed = p_.velocity(i).norm();
    p_.still_time[i] = speed < s_.stop_speed ? p_.still_time[i] + step : 0.0;
    if (p_.still_time[i] < s_.stop_duration) return;
    const BasalResistance& r = resistance_[i];
    const double v = s_.stop_speed;
    const double holding = r.yield + r.linear * v + r.quadratic * v * v;
    const double driving = std::sqrt(p_.ax[i] * p_.ax[i] + p_.ay[i] * p_.ay[i] + p_.az[i] * p_.az[i]);
    if (driving > holding) return;
    p_.state[i] = ParticleState::deposited;
    limiter_level_[i] = -1;
    p_.vx[i] = p_.vy[i] = p_.vz[i] = 0.0;
    p_.ax[i] = p_.ay[i] = p_.az[i] = 0.0;
  });
}

// Entrainment (paper 4.1, last paragraph) over the step each listed flowing particle has just
// finished, one call per step length, in index order; the energy the new mass brings (its
// potential and its share of the columns' internal energy) is counted for the guard.
void MudflowRun::entrain(const std::vector<std::uint32_t>& list) {
  if (!entrainment_) return;
  std::uint64_t levels = 0;  // bit l: some listed flowing particle finished a step of level l
  for (const std::uint32_t i : list) {
    if (p_.state[i] == ParticleState::flowing) levels |= std::uint64_t{1} << p_.level[i];
  }
  for (int level = 0; level <= finest_level_; ++level) {
    if ((levels >> level & 1u) == 0) continue;
    erode_flags_.assign(p_.size(), 0);
    for (const std::uint32_t i : list) {
      if (p_.state[i] == ParticleState::flowing && p_.level[i] == level) erode_flags_[i] = 1;
    }
    mass_before_.assign(p_.mass.begin(), p_.mass.end());
    entrained_volume_ += entrainment_->erode(p_, erode_flags_, step_of(level), eroded_);
    for (const std::uint32_t i : list) {
      const double gained = p_.mass[i] - mass_before_[i];
      if (gained == 0.0) continue;
      energy_source_ += gained * s_.gravity * (p_.z[i] - reference_elevation_ + normals_.z[i] * p_.depth[i]);
    }
  }
}

// Every flowing particle moves on the ground for `duration` (s); one that leaves the valid area
// (or, on a window, crosses its halo's edge) gives its mass (and its energy, for the guard) to the
// outflow and drops out of every sum (mass 0) until the coarse step ends.
void MudflowRun::drift(const std::vector<std::uint32_t>& list, double duration) {
  for_each_listed(list, [&](std::size_t i) {
    const bool on_ground = drift_on_ground(ground_, p_, i, duration, normals_, node_slopes());
    const bool in_window = !s_.window_edge || s_.window_edge->contains(p_.x[i], p_.y[i]);
    if (on_ground && in_window) return;
    outside_[i] = on_ground ? 2 : 1;
    limiter_level_[i] = -1;
    const double m = p_.mass[i];
    outflow_mass_[i] = m;
    outflow_energy_[i] = m * (0.5 * p_.velocity(i).squaredNorm() + s_.gravity * (p_.z[i] - reference_elevation_) +
                              0.5 * s_.gravity * normals_.z[i] * p_.depth[i]);
    p_.mass[i] = 0.0;
    p_.vx[i] = p_.vy[i] = p_.vz[i] = 0.0;
  });
}

// One coarse step of block time stepping (paper 4.2): every flowing particle opens a step of its
// level; at each tick where some steps end, every flowing particle drifts to that time and the
// particles whose steps end get their densities and forces, close their steps, entrain, choose
// new levels and open new steps. At the end of the coarse step all steps end together.
void MudflowRun::coarse_step() {
  const std::uint64_t end = ticks_per_step(0, finest_level_);
  const double tick_length = std::ldexp(coarse_step_, -finest_level_);
  std::vector<std::uint32_t> moving, active;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (flowing(i)) moving.push_back(static_cast<std::uint32_t>(i));
    limiter_level_[i] = -1;  // until the particle opens a step
  }
  open_steps(moving, 0);
  for (const std::uint32_t i : moving) next_sync_[i] = ticks_per_step(p_.level[i], finest_level_);
  std::uint64_t now = 0;
  while (true) {
    std::uint64_t next = end;
    for (const std::uint32_t i : moving) next = std::min(next, next_sync_[i]);
    drift(moving, static_cast<double>(next - now) * tick_length);
    now = next;
    if (now >= end) break;
    active.clear();
    for (const std::uint32_t i : moving) {
      if (outside_[i] == 0 && next_sync_[i] == now) active.push_back(i);
    }
    evaluate(active);
    close_steps(active);
    entrain(active);
    std::erase_if(active, [&](std::uint32_t i) { return p_.state[i] != ParticleState::flowing; });
    open_steps(active, now);
    for (const std::uint32_t i : active) next_sync_[i] = now + ticks_per_step(p_.level[i], finest_level_);
    std::erase_if(moving, [&](std::uint32_t i) { return !flowing(i); });
  }
  compact_and_sort();
  evaluate_all();
  std::vector<std::uint32_t> closing;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (flowing(i)) closing.push_back(static_cast<std::uint32_t>(i));
  }
  close_steps(closing);
  entrain(closing);
}

// Fission then fusion (paper 4.2) on the synchronised particles, with their conservation measured.
bool MudflowRun::adapt() {
  if (!s_.adaptive) return false;
  const auto conserve = [&](auto&& change) {
    const double mass_before = p_.total_mass();
    const Eigen::Vector3d momentum_before = p_.total_momentum();
    double scale = 0;
    for (std::size_t i = 0; i < p_.size(); ++i) scale += p_.mass[i] * p_.velocity(i).norm();
    const std::size_t count = change();
    if (count == 0) return count;
    adaptivity_mass_change_ =
        std::max(adaptivity_mass_change_, std::abs(p_.total_mass() - mass_before) / mass_before);
    if (scale > 0.0) {
      adaptivity_momentum_change_ =
          std::max(adaptivity_momentum_change_, (p_.total_momentum() - momentum_before).norm() / scale);
    }
    return count;
  };
  rebuild_pairs(p_.radius, p_.size());
  // Crowded fusion (section 8 of docs/mudflow.md): groups merge while the merged particle sums
  // over at most crowded_merge finest support radii, with half the split threshold as their
  // contrast threshold (hysteresis); a particle held at the finest radius does not split.
  const bool crowded = std::isfinite(smallest_smoothing_);
  const FissionRule fission{s_.split_threshold, s_.particle_size, crowded ? smallest_smoothing_ : 0.0};
  const std::size_t split = conserve([&] { return split_particles(p_, pairs_, ground_, fission); });
  rebuild_pairs(p_.radius, p_.size());
  const FusionRule fusion{s_.merge_threshold, s_.merge_speed, s_.particle_size * std::ldexp(1.0, s_.coarse_levels),
                          crowded ? s_.crowded_merge * smallest_smoothing_ : 0.0, 0.5 * s_.split_threshold};
  const std::size_t merged = conserve([&] { return merge_particles(p_, pairs_, ground_, fusion); });
  splits_ += split;
  merges_ += merged;
  return split + merged > 0;
}

// At the end of a coarse step: drops the particles that left the valid area, counting their
// volume as outflow, and puts the others in the order of square cells of the largest support
// radius (row by row, then by index), so that neighbours lie close in memory. The order depends only on
// the positions, so the result does not depend on the thread count.
void MudflowRun::compact_and_sort() {
  const double bin = p_.size() == 0 ? 1.0 : *std::max_element(p_.radius.begin(), p_.radius.end());
  double min_x = std::numeric_limits<double>::infinity(), min_y = min_x;
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (outside_[i] != 0) {
      outflow_volume_ += outflow_mass_[i] / s_.mud_density;
      if (outside_[i] == 2) halo_outflow_volume_ += outflow_mass_[i] / s_.mud_density;
      energy_source_ -= outflow_energy_[i];
      continue;
    }
    min_x = std::min(min_x, p_.x[i]);
    min_y = std::min(min_y, p_.y[i]);
  }
  std::vector<std::pair<std::uint64_t, std::uint32_t>> keys;
  keys.reserve(p_.size());
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (outside_[i] != 0) continue;
    const auto col = static_cast<std::uint64_t>((p_.x[i] - min_x) / bin);
    const auto row = static_cast<std::uint64_t>((p_.y[i] - min_y) / bin);
    keys.push_back({(row << 32) | col, static_cast<std::uint32_t>(i)});
  }
  std::sort(keys.begin(), keys.end());
  std::vector<std::uint32_t> order(keys.size());
  FootNormals normals;
  normals.resize(keys.size());
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const std::uint32_t i = keys[k].second;
    order[k] = i;
    normals.x[k] = normals_.x[i];
    normals.y[k] = normals_.y[i];
    normals.z[k] = normals_.z[i];
  }
  p_.reorder(order);
  normals_ = std::move(normals);
  resize_work();
  reset_smoothing();
}

void MudflowRun::record(MudflowResult& result) {
  const FlowEnergy energy = flow_energy(p_, normals_, s_.gravity, reference_elevation_);
  MudflowHistoryPoint point;
  point.time = time();
  point.kinetic_energy = energy.kinetic;
  point.potential_energy = energy.potential;
  point.internal_energy = energy.internal;
  point.mass = p_.total_mass();
  point.momentum = p_.total_momentum();
  for (std::size_t i = 0; i < p_.size(); ++i) {
    if (p_.state[i] == ParticleState::flowing) {
      ++point.flowing;
    } else {
      ++point.deposited;
    }
  }
  result.history.push_back(point);
  result.peak_kinetic_energy = std::max(result.peak_kinetic_energy, energy.kinetic);
  result.peak_particles = std::max(result.peak_particles, p_.size());
}

void MudflowRun::snapshot(MudflowResult& result) const {
  ParticleSnapshot shot;
  shot.time = time();
  shot.x = p_.x;
  shot.y = p_.y;
  shot.z = p_.z;
  shot.depth = p_.depth;
  shot.mass = p_.mass;
  shot.radius = smoothing_;
  shot.speed.resize(p_.size());
  for (std::size_t i = 0; i < p_.size(); ++i) shot.speed[i] = p_.velocity(i).norm();
  result.snapshots.push_back(std::move(shot));
}

MudflowResult MudflowRun::run() {
  MudflowResult result;
  result.threads = threads_;
  result.initial_particles = p_.size();
  result.released_volume = p_.total_mass() / s_.mud_density;
  if (p_.size() == 0) throw InputError("mudflow: the release holds no mud inside the DEM's valid area");
  reference_elevation_ = *std::min_element(p_.z.begin(), p_.z.end());
  refresh();
  record(result);
  maps_.sample(p_, 0.0);
  double last_map = 0.0;
  double next_map = s_.map_interval;
  double next_snapshot = s_.snapshot_interval;
  if (s_.snapshot_interval > 0) snapshot(result);

  const double slack = kTimeSlack * coarse_step_;
  RunEndEstimate end_estimate(s_.duration, s_.stop_energy_fraction);
  const auto run_started = std::chrono::steady_clock::now();
  while (true) {
    const auto started = std::chrono::steady_clock::now();
    const std::uint64_t steps_before = particle_steps_;
    if (adapt()) refresh();
    const ParticleSet saved = s_.guard ? p_ : ParticleSet{};
    const std::optional<Entrainment> saved_entrainment = s_.guard ? entrainment_ : std::nullopt;
    const Grid<float> saved_eroded = s_.guard ? eroded_ : Grid<float>{};
    const double saved_entrained = entrained_volume_, saved_outflow = outflow_volume_,
                 saved_halo_outflow = halo_outflow_volume_;
    const FlowEnergy before = flow_energy(p_, normals_, s_.gravity, reference_elevation_);
    while (true) {
      energy_source_ = 0;
      coarse_step();
      if (!s_.guard) break;
      const FlowEnergy after = flow_energy(p_, normals_, s_.gravity, reference_elevation_);
      if (all_finite(p_) && !energy_blew_up(before, after, energy_source_)) break;
      if (depth_ >= s_.max_retries) {
        throw NumericalFailure("mudflow: unstable at t = " + std::to_string(time()) + " s after " +
                               std::to_string(s_.max_retries) + " step halvings");
      }
      ++depth_;
      ++guard_retries_;
      p_ = saved;
      entrainment_.reset();
      if (saved_entrainment) entrainment_.emplace(*saved_entrainment);
      eroded_ = saved_eroded;
      entrained_volume_ = saved_entrained;
      outflow_volume_ = saved_outflow;
      halo_outflow_volume_ = saved_halo_outflow;
      refresh();
    }
    loops_.record(std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count(),
                  particle_steps_ - steps_before);
    ++coarse_steps_;
    const double t = time();
    record(result);
    if (t + slack >= next_map) {
      maps_.sample(p_, t);
      last_map = t;
      while (next_map <= t + slack) next_map += s_.map_interval;
    }
    if (s_.snapshot_interval > 0 && t + slack >= next_snapshot) {
      snapshot(result);
      while (next_snapshot <= t + slack) next_snapshot += s_.snapshot_interval;
    }
    const MudflowHistoryPoint& now = result.history.back();
    if (progress_ != nullptr) {
      end_estimate.record(t, now.kinetic_energy,
                          std::chrono::duration<double>(std::chrono::steady_clock::now() - run_started).count());
      progress_->report(end_estimate.fraction_done(), progress_phase(end_estimate));
      if (progress_->cancelled()) throw Cancelled();
    }
    if (p_.size() == 0) {
      result.end = MudflowEnd::outflow;
      break;
    }
    if (now.flowing == 0 || now.kinetic_energy < s_.stop_energy_fraction * result.peak_kinetic_energy) {
      result.end = MudflowEnd::energy;
      break;
    }
    if (t + slack >= s_.duration) {
      result.end = MudflowEnd::duration;
      break;
    }
  }

  const double t = time();
  if (progress_ != nullptr) {
    char phase[96];
    std::snprintf(phase, sizeof phase, "mud flow: simulated %.1f s (end: %s)", t, to_string(result.end));
    progress_->report(1.0, phase);
  }
  if (last_map + slack < t) maps_.sample(p_, t);
  if (s_.snapshot_interval > 0 && (result.snapshots.empty() || result.snapshots.back().time < t)) snapshot(result);
  if (entrainment_) {
    for (std::size_t cell = 0; cell < eroded_.size(); ++cell) {
      if (eroded_[cell] > 0.0f) maps_.add_erosion(cell, eroded_[cell]);
    }
  }
  result.deposited_volume = maps_.deposit(p_);
  result.layers = maps_.take_layers();
  result.simulated_time = t;
  result.entrained_volume = entrained_volume_;
  result.outflow_volume = outflow_volume_;
  result.halo_outflow_volume = halo_outflow_volume_;
  result.final_particles = p_.size();
  result.splits = splits_;
  result.merges = merges_;
  result.particle_steps = particle_steps_;
  result.coarse_steps = coarse_steps_;
  result.guard_retries = guard_retries_;
  result.adaptivity_mass_change = adaptivity_mass_change_;
  result.adaptivity_momentum_change = adaptivity_momentum_change_;
  return result;
}

}  // namespace

MudflowResult run_mudflow(const GroundModel& ground, const ReleaseSet& release, const Grid<float>* erodible,
                          const MudflowSettings& settings, Progress* progress) {
  validate(settings);
  // Every parallel region of the run, the adaptivity's included, uses the run's thread count.
  const ThreadCount thread_count(settings.threads > 0 ? settings.threads : omp_get_max_threads());
  MudflowRun run(ground, release, erodible, settings, progress);
  return run.run();
}

}  // namespace talus
