// `talus mudflow` in the engine (paper 4, docs/architecture.md section 2): release the mud as smoothed
// particles on the ground model, move them with the shallow-flow SPH equations and the chosen
// rheology, adapt particle sizes and time steps (paper 4.2), entrain erodible material, deposit
// stopped mud, and gather the mud-flow layers. Same seed and inputs, same result, whatever the
// thread count.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "talus/core/grid.hpp"
#include "talus/core/progress.hpp"
#include "talus/core/release.hpp"
#include "talus/core/tile_bounds.hpp"
#include "talus/ground/ground_model.hpp"
#include "talus/mudflow/flow_forces.hpp"
#include "talus/mudflow/flow_maps.hpp"
#include "talus/mudflow/release_particles.hpp"
#include "talus/mudflow/rheology.hpp"

namespace talus {

struct MudflowSettings {
  // Run.
  double duration = 300;            // s: longest simulated time
  double stop_energy_fraction = 0.01;  // the run ends when kinetic energy falls below this x its peak (-)
  std::uint64_t seed = 1;           // jitter of the particles' initial places
  // A flow on a window of the region (issue 19, item 4; docs/study.md, "Tiles"): the window's halo
  // edge; a particle that crosses it leaves the flow as outflow, counted in halo_outflow_volume.
  std::optional<TileBounds> window_edge;
  int threads = 0;                  // 0: all cores
  int parallel_particles = 256;     // per-particle loops over fewer particles run on one thread
  int parallel_check_period = 20;   // coarse steps between timed trials of one thread against all for the
                                    // per-particle loops (parallel_loop_choice.hpp); 0: always all threads
  int interleaved_particles = 4096; // threads with at least this many particles to evaluate compute each one's
                                    // forces right after the densities they read (evaluation_order.hpp)
  // Mud and particles.
  double mud_density = 2000;        // rho0 (kg/m3)
  double gravity = 9.81;            // m/s2
  double particle_size = 2.5;       // m: spacing of the finest particles
  ReleaseThickness release_thickness = ReleaseThickness::normal;  // how a release depth is measured
  PressureColumn pressure = PressureColumn::normal;  // whose weight the pressure is (flow_forces.hpp)
  bool adaptive = true;             // fission/fusion and individual time steps (paper 4.2)
  int coarse_levels = 2;            // adaptive: sizes particle_size x 2^k, k = 0..coarse_levels; released at the coarsest
  double split_threshold = 0.5;     // split when size x |grad P| / P exceeds this (-)
  double merge_threshold = 0.1;     // a calm group merges when every member's size x |grad P| / P is below this (-)
  double merge_speed = 0.5;         // and its members' velocities differ by less than this (m/s)
  double crowded_merge = 1.5;       // > 0: crowded groups merge while the merged particle sums over at most this many
                                    // finest support radii (-; docs/mudflow.md section 8); 0: off
  // Time steps (paper 4.2; Courant condition).
  double courant = 0.3;             // C in dt = C min(s / (c + w), sqrt(s / |a|)), w the neighbours' closing speed (-)
  double cells_per_step = 0;        // a step crosses at most this many DEM cells (-); 0: automatic, see below
  double longest_step = 0.5;        // s: level-0 step
  int deepest_level = 12;           // steps are longest_step / 2^level, level <= this
  bool guard = true;                // detect blow-up and retry with halved steps
  int max_retries = 6;              // halvings before NumericalFailure (exit code 3)
  double unguarded_step = 0;        // s: > 0 forces this global step and ignores the Courant condition (tests)
  // Ground contact.
  bool curvature = true;            // the basal normal stress includes the centripetal term rho0 h u^2 kappa
  bool node_normals = false;        // normals interpolated between the nodes' (smooth), not the squares' own
  bool step_normal = false;         // gravity along the normal averaged over the step ahead, not the foot's
  double curvature_span = 20;       // m: kappa is measured between the ground normals this far apart along
                                    // the velocity (at least one cell and the particle's spacing)
  // Rheology, deposition and entrainment.
  RheologyParameters rheology;
  double stop_speed = 0.05;         // m/s: slower than this for stop_duration, and held by the bed, it deposits
  double stop_duration = 2;         // s
  double entrainment_rate = 0.01;   // E (1/m): erosion rate E h |u| (m/s), McDougall & Hungr 2005
  // Outputs.
  double arrival_depth = 0.05;      // m: a cell is reached when its flow depth first exceeds this
  double map_interval = 0.5;        // s: flow depth, velocity and pressure maxima are sampled this often
  double snapshot_interval = 0;     // s: > 0 keeps particle snapshots this often
};

// The ground limit of the time steps (docs/mudflow.md section 7): cells_per_step when given, else
// 1 cell in adaptive runs with crowded fusion, where the deep mud's particles are coarse and the
// flow at one cell per step stays with the time-converged run, and half a cell otherwise.
double cells_crossed_per_step(const MudflowSettings& settings);

enum class MudflowEnd { duration, energy, outflow };
const char* to_string(MudflowEnd end);

// The particles at one time (for the GeoPackage the QGIS temporal controller plays).
struct ParticleSnapshot {
  double time = 0;                  // s
  std::vector<double> x, y, z;      // m
  std::vector<double> depth;        // m
  std::vector<double> speed;        // m/s
  std::vector<double> mass;         // kg
  std::vector<double> radius;       // m: support radius of the SPH sums (flow_density.hpp, smoothing radius)
};

// The flow at the end of one coarse step (the run's history, for checks and run.json).
struct MudflowHistoryPoint {
  double time = 0;                  // s
  double kinetic_energy = 0;        // J
  double potential_energy = 0;      // J: m g (z - lowest release elevation), feet of the columns
  double internal_energy = 0;       // J: m g cos(theta) h / 2, the columns' own potential
  double mass = 0;                  // kg
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();  // kg m/s
  std::size_t flowing = 0, deposited = 0;              // particles
};

struct MudflowResult {
  FlowLayers layers;
  std::vector<ParticleSnapshot> snapshots;
  MudflowEnd end = MudflowEnd::duration;
  double simulated_time = 0;        // s
  double released_volume = 0;       // m3
  double entrained_volume = 0;      // m3
  double deposited_volume = 0;      // m3: material on the DEM at the end
  double outflow_volume = 0;        // m3: material that left the DEM's valid area (or the window's halo)
  double halo_outflow_volume = 0;   // m3: of outflow_volume, what crossed settings.window_edge
  std::size_t initial_particles = 0, peak_particles = 0, final_particles = 0;
  std::size_t splits = 0, merges = 0;
  std::uint64_t particle_steps = 0; // force evaluations of one particle, summed
  std::uint64_t coarse_steps = 0;   // level-0 steps
  std::size_t guard_retries = 0;
  double peak_kinetic_energy = 0;   // J
  int threads = 1;
  std::vector<MudflowHistoryPoint> history;  // one point at the start and after every coarse step
  // Conservation across the adaptivity (paper 4.2): the largest change of total mass (relative)
  // and of total momentum (relative to the sum of m |u|) across one split or merge call (-).
  double adaptivity_mass_change = 0;
  double adaptivity_momentum_change = 0;
};

// Runs the mud flow. release.depth holds the release depth (m) per DEM cell; release points
// release a cell-sized column of their depth. erodible (m per DEM cell) may be null.
// Throws InputError for settings out of range, NumericalFailure when the guard gives up, and
// Cancelled when progress asks to stop.
MudflowResult run_mudflow(const GroundModel& ground, const ReleaseSet& release, const Grid<float>* erodible,
                          const MudflowSettings& settings, Progress* progress);

}  // namespace talus
