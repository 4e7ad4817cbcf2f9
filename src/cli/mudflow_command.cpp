// `talus mudflow` (DESIGN.md section 3, issue 5): the adaptive smoothed-particle mud flow of
// paper section 4 on the user's scene, every mud-flow layer, optional particle snapshots and
// run.json.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "intensity_layer.hpp"
#include "mudflow_materials.hpp"
#include "parameter_table.hpp"
#include "run_project.hpp"
#include "terminal_progress.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/layer_writer.hpp"
#include "talus/gis/particle_snapshot_writer.hpp"
#include "talus/gis/run_record.hpp"
#include "talus/gis/scene.hpp"
#include "talus/mudflow/mudflow_simulation.hpp"

namespace talus::cli {
namespace {

struct MudflowOptions {
  gis::SceneInputs inputs;
  std::filesystem::path out;
  std::filesystem::path scenario;
  std::string material = MudflowMaterials::built_in().default_name();  // --material, [mud] material
  std::string rheology = to_string(RheologyParameters{}.rheology);
  std::string adaptive = "on";  // --adaptive on|off, into settings.adaptive
  std::string release_thickness = to_string(ReleaseThickness::normal);  // into settings.release_thickness
  double release_depth = 0;            // m: --depth, [mud] release_depth; 0: the release file's depths
  std::string depth_field = "depth";   // --depth-field, [mud] depth_field
  std::string snapshot_start = gis::kDefaultSnapshotStart;  // --start-time, [outputs] snapshot_start
  std::int64_t snapshot_start_seconds = 0;                  // s after 1970-01-01, from snapshot_start
  std::string project = "on";  // --project on|off, [outputs] project
  std::string intensity = kDefaultIntensity;                // --intensity, [outputs] intensity
  MudflowSettings settings;
  std::vector<std::string> command_line;
};

// Particle snapshots: the closest interval (s) and the most snapshots a run writes.
constexpr double kMinSnapshotInterval = 0.01;
constexpr double kMaxSnapshots = 100000.0;

// The parameters that have a command-line flag: a flag given pins its parameter against the
// scenario file, and messages about the parameter name the flag.
struct Flag {
  const char* section;
  const char* name;
  const char* option;
};
constexpr Flag kFlags[] = {{"run", "duration", "--duration"},       {"run", "seed", "--seed"},
                           {"run", "threads", "--threads"},         {"mud", "material", "--material"},
                           {"mud", "particle_size", "--particle-size"}, {"adaptivity", "adaptive", "--adaptive"},
                           {"rheology", "rheology", "--rheology"},  {"outputs", "snapshot_interval", "--snapshots"},
                           {"mud", "release_depth", "--depth"},     {"mud", "depth_field", "--depth-field"},
                           {"outputs", "snapshot_start", "--start-time"}, {"outputs", "intensity", "--intensity"},
                           {"outputs", "project", "--project"}};

// Every MudflowSettings field (mudflow_simulation.hpp, rheology.hpp) as a scenario parameter.
ParameterTable parameter_table(MudflowOptions& o) {
  ParameterTable table;
  auto& s = o.settings;
  table.add("run", "duration", "s", "longest simulated time", &s.duration);
  table.add("run", "stop_energy_fraction", "-", "the run ends when the kinetic energy falls below this fraction of its peak",
            &s.stop_energy_fraction);
  table.add("run", "seed", "", "seed of the jitter of the particles' initial places", &s.seed);
  table.add("run", "threads", "", "threads (0: all cores); the layers do not depend on it", &s.threads);
  table.add("run", "parallel_particles", "", "loops over fewer particles than this run on one thread", &s.parallel_particles);
  table.add("run", "parallel_check_period", "",
            "coarse steps between timed trials of one thread against all threads for the particle loops, which then "
            "run the faster way (0: always all threads); the layers do not depend on it",
            &s.parallel_check_period);
  table.add("run", "interleaved_particles", "",
            "threads with at least this many particles to evaluate compute each particle's forces as soon as the "
            "densities they read are done, while its neighbour list is in the cache; fewer: all densities first; the "
            "layers do not depend on it",
            &s.interleaved_particles);
  table.add("mud", "material", "",
            "material preset that sets the rheology, its parameters and the density before the scenario's own keys: " +
                MudflowMaterials::built_in().name_list(),
            &o.material);
  table.add("mud", "density", "kg/m3", "bulk density of the mud rho0", &s.mud_density);
  table.add("mud", "gravity", "m/s2", "gravitational acceleration", &s.gravity);
  table.add("mud", "particle_size", "m", "spacing of the finest particles", &s.particle_size);
  table.add("mud", "release_thickness", "",
            "how a release depth is measured: normal (to the ground, the thin-layer convention) or vertical",
            &o.release_thickness);
  table.add("mud", "release_depth", "m",
            "one release depth for every release cell, polygon and point, whatever the release file holds (0: the "
            "file's depths)",
            &o.release_depth);
  table.add("mud", "depth_field", "", "the attribute of a vector release that holds each feature's depth (m)",
            &o.depth_field);
  table.add("adaptivity", "adaptive", "", "particle fission and fusion and individual time steps (paper 4.2)", &s.adaptive);
  table.add("adaptivity", "coarse_levels", "",
            "particle sizes are particle_size x 2^k, k = 0..coarse_levels; the release uses the coarsest", &s.coarse_levels);
  table.add("adaptivity", "split_threshold", "-", "a particle splits when its size x |grad P| / P exceeds this",
            &s.split_threshold);
  table.add("adaptivity", "merge_threshold", "-", "a calm group merges when each member's size x |grad P| / P is below this",
            &s.merge_threshold);
  table.add("adaptivity", "merge_speed", "m/s", "and its members' velocities differ by less than this", &s.merge_speed);
  table.add("time_steps", "courant", "-",
            "C in dt = C min(s / (c + w), sqrt(s / |a|)), w the fastest closing speed of a neighbour", &s.courant);
  table.add("time_steps", "cells_per_step", "-", "a particle's step crosses at most this many DEM cells",
            &s.cells_per_step);
  table.add("time_steps", "longest_step", "s", "step of level 0; level k steps are longest_step / 2^k", &s.longest_step);
  table.add("time_steps", "deepest_level", "", "deepest step level", &s.deepest_level);
  table.add("time_steps", "guard", "", "detect blown-up steps and retry them with halved steps", &s.guard);
  table.add("time_steps", "max_retries", "", "step halvings before a run fails with exit code 3", &s.max_retries);
  table.add("time_steps", "unguarded_step", "s", "> 0: one global step that ignores the Courant condition (tests of the guard)",
            &s.unguarded_step);
  table.add("contact", "curvature", "",
            "the basal normal stress includes the centripetal term rho0 h u^2 kappa of the ground's curvature", &s.curvature);
  table.add("contact", "curvature_span", "m",
            "kappa is measured between the ground normals this far apart along the velocity (at least one DEM cell and "
            "the particle's spacing)",
            &s.curvature_span);
  auto& r = s.rheology;
  table.add("rheology", "rheology", "", "basal resistance: viscous, coulomb, voellmy or bingham", &o.rheology);
  table.add("rheology", "friction", "-", "Coulomb friction coefficient mu of the basal resistance (coulomb, voellmy)",
            &r.friction);
  table.retire("rheology", "friction_factor",
               "no longer used: give [rheology] friction, the friction coefficient mu itself (0-1); the lithology no "
               "longer sets the mud's friction");
  table.add("rheology", "turbulence", "m/s2", "turbulence coefficient xi of Voellmy", &r.turbulence);
  table.add("rheology", "viscosity", "Pa s", "dynamic viscosity eta (viscous and Bingham)", &r.viscosity);
  table.add("rheology", "yield_stress", "Pa", "yield stress tau_y of Bingham", &r.yield_stress);
  table.add("rheology", "internal_viscosity", "m2/s", "kinematic viscosity of the internal friction between particles",
            &r.internal_viscosity);
  table.add("deposition", "stop_speed", "m/s", "mud slower than this for stop_duration, and held by the bed, deposits",
            &s.stop_speed);
  table.add("deposition", "stop_duration", "s", "how long the mud must stay slower than stop_speed", &s.stop_duration);
  table.add("entrainment", "rate", "1/m", "entrainment rate E: the bed erodes at E h |u| (m/s) where erodible material lies",
            &s.entrainment_rate);
  table.add("outputs", "arrival_depth", "m", "a cell is reached when its flow depth first exceeds this", &s.arrival_depth);
  table.add("outputs", "map_interval", "s", "flow depth, velocity and pressure maxima are sampled this often",
            &s.map_interval);
  table.add("outputs", "snapshot_interval", "s", "> 0: particles.gpkg holds the particles this often", &s.snapshot_interval);
  table.add("outputs", "project", "",
            "on: also write project.qgz, hillshade.tif and quicklook/*.png with QGIS (python3-qgis); off: not", &o.project);
  table.add("outputs", "intensity", "",
            "intensity classes of intensity.tif: a built-in guideline (foen-2016), a guideline file FILE.toml, or none",
            &o.intensity);
  table.add("outputs", "snapshot_start", "",
            "date-time of the release on particles.gpkg's clock, YYYY-MM-DDTHH:MM:SS (no time zone)", &o.snapshot_start);
  return table;
}

// A number as a user typed it: "0", "2.5", "1e-05".
std::string number_text(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// Refuses out-of-range parameters with one line that names where the value came from: the flag
// given on the command line, or the scenario file and its [section] key.
class ParameterCheck {
 public:
  ParameterCheck(const ParameterTable& table, const std::filesystem::path& scenario) : table_(table), scenario_(scenario) {}

  void require(bool ok, const std::string& section, const std::string& name, const std::string& value,
               const std::string& expected) const {
    if (ok) return;
    throw InputError(where(section, name) + " " + value + ": " + expected);
  }
  void require(bool ok, const std::string& section, const std::string& name, double value, const std::string& expected) const {
    require(ok && std::isfinite(value), section, name, number_text(value), expected);
  }

 private:
  std::string where(const std::string& section, const std::string& name) const {
    if (table_.given_on_command_line(section, name)) {
      for (const Flag& flag : kFlags) {
        if (section == flag.section && name == flag.name) return flag.option;
      }
    }
    const std::string key = "[" + section + "] " + name;
    return scenario_.empty() ? key : scenario_.string() + " (scenario): " + key;
  }
  const ParameterTable& table_;
  std::filesystem::path scenario_;
};

// --adaptive on|off.
bool parse_on_off(const std::string& text) {
  if (text == "on") return true;
  if (text == "off") return false;
  throw InputError("--adaptive " + text + ": use on or off");
}

// The material preset named by --material, the scenario's [mud] material or the default, under
// the scenario's own keys and the flags (docs/mudflow.md, "Materials").
void apply_material(const MudflowOptions& o, ParameterTable& table) {
  const MudflowMaterials& materials = MudflowMaterials::built_in();
  const ParameterCheck check(table, o.scenario);
  check.require(materials.contains(o.material), "mud", "material", o.material,
                "expected one of " + materials.name_list());
  materials.apply(o.material, table);
}

// Every parameter within the range the model is meant for (docs/mudflow.md).
void validate(MudflowOptions& o, const ParameterTable& table) {
  const ParameterCheck check(table, o.scenario);
  const auto& s = o.settings;
  const auto& r = s.rheology;
  const std::string rheology = o.rheology;
  check.require(rheology == "viscous" || rheology == "coulomb" || rheology == "voellmy" || rheology == "bingham", "rheology",
                "rheology", rheology, "use viscous, coulomb, voellmy or bingham");
  o.settings.rheology.rheology = parse_rheology(rheology);
  check.require(o.release_thickness == "normal" || o.release_thickness == "vertical", "mud", "release_thickness",
                o.release_thickness, "use normal or vertical");
  o.settings.release_thickness = parse_release_thickness(o.release_thickness);
  check.require(o.release_depth == 0.0 || (o.release_depth >= 0.01 && o.release_depth <= gis::kMaxReleaseDepth), "mud", "release_depth",
                o.release_depth, "expected 0 (the release file's depths) or a depth of 0.01-100 m");
  check.require(!o.depth_field.empty(), "mud", "depth_field", o.depth_field, "expected an attribute name");
  check.require(o.release_depth == 0.0 || o.depth_field == "depth", "mud", "depth_field", o.depth_field,
                "give either a depth attribute or one release depth, not both");
  o.inputs.release_depth.field = o.depth_field;
  if (o.release_depth > 0.0) o.inputs.release_depth.uniform = o.release_depth;
  check.require(s.duration > 0.0 && s.duration <= 86400.0, "run", "duration", s.duration, "expected a time > 0 s, at most a day");
  check.require(s.stop_energy_fraction >= 0.0 && s.stop_energy_fraction < 1.0, "run", "stop_energy_fraction",
                s.stop_energy_fraction, "expected a fraction in [0, 1)");
  check.require(s.threads >= 0, "run", "threads", s.threads, "expected 0 (all cores) or more");
  check.require(s.parallel_particles >= 1, "run", "parallel_particles", s.parallel_particles, "expected 1 or more");
  check.require(s.interleaved_particles >= 1, "run", "interleaved_particles", s.interleaved_particles,
                "expected 1 or more");
  check.require(s.parallel_check_period == 0 || s.parallel_check_period >= 3, "run", "parallel_check_period",
                s.parallel_check_period, "expected 0 (always all threads) or 3 or more coarse steps");
  check.require(s.mud_density >= 100.0 && s.mud_density <= 3000.0, "mud", "density", s.mud_density,
                "expected 100-3000 kg/m3");
  check.require(s.gravity > 0.0 && s.gravity <= 30.0, "mud", "gravity", s.gravity, "expected 0-30 m/s2");
  check.require(s.particle_size > 0.0, "mud", "particle_size", s.particle_size, "expected a spacing > 0 m");
  check.require(s.coarse_levels <= 8, "adaptivity", "coarse_levels", s.coarse_levels, "expected 0-8");
  check.require(s.split_threshold > 0.0, "adaptivity", "split_threshold", s.split_threshold, "expected a ratio > 0");
  check.require(s.merge_threshold >= 0.0 && s.merge_threshold < s.split_threshold, "adaptivity", "merge_threshold",
                s.merge_threshold, "expected a ratio >= 0 below split_threshold " + number_text(s.split_threshold));
  check.require(s.merge_speed >= 0.0, "adaptivity", "merge_speed", s.merge_speed, "expected a speed >= 0 m/s");
  check.require(s.courant > 0.0 && s.courant <= 1.0, "time_steps", "courant", s.courant, "expected a number in (0, 1]");
  check.require(s.cells_per_step > 0.0 && s.cells_per_step <= 10.0, "time_steps", "cells_per_step", s.cells_per_step,
                "expected a number of cells in (0, 10]");
  check.require(s.longest_step > 0.0 && s.longest_step <= 10.0, "time_steps", "longest_step", s.longest_step,
                "expected a step > 0 s, at most 10 s");
  check.require(s.deepest_level <= 30, "time_steps", "deepest_level", s.deepest_level, "expected 0-30");
  check.require(s.max_retries <= 20, "time_steps", "max_retries", s.max_retries, "expected 0-20");
  check.require(s.unguarded_step >= 0.0, "time_steps", "unguarded_step", s.unguarded_step, "expected 0 (off) or a step > 0 s");
  check.require(s.curvature_span >= 0.0 && s.curvature_span <= 1000.0, "contact", "curvature_span", s.curvature_span,
                "expected a length in 0-1000 m");
  check.require(r.friction >= 0.0 && r.friction <= 1.0, "rheology", "friction", r.friction,
                "expected a coefficient in [0, 1]");
  check.require(r.turbulence > 0.0, "rheology", "turbulence", r.turbulence, "expected a coefficient > 0 m/s2");
  check.require(r.viscosity >= 0.0, "rheology", "viscosity", r.viscosity, "expected a viscosity >= 0 Pa s");
  check.require(r.yield_stress >= 0.0, "rheology", "yield_stress", r.yield_stress, "expected a stress >= 0 Pa");
  check.require(r.internal_viscosity >= 0.0, "rheology", "internal_viscosity", r.internal_viscosity,
                "expected a viscosity >= 0 m2/s");
  check.require(s.stop_speed >= 0.0, "deposition", "stop_speed", s.stop_speed, "expected a speed >= 0 m/s");
  check.require(s.stop_duration >= 0.0, "deposition", "stop_duration", s.stop_duration, "expected a time >= 0 s");
  check.require(s.entrainment_rate >= 0.0, "entrainment", "rate", s.entrainment_rate, "expected a rate >= 0 1/m");
  check.require(s.arrival_depth > 0.0, "outputs", "arrival_depth", s.arrival_depth, "expected a depth > 0 m");
  check.require(s.map_interval > 0.0, "outputs", "map_interval", s.map_interval, "expected an interval > 0 s");
  const bool snapshots_flag = table.given_on_command_line("outputs", "snapshot_interval");
  // At least kMinSnapshotInterval apart and at most kMaxSnapshots in the run, so that a tiny
  // interval is refused now, not after the whole flow when particles.gpkg is written (issue 18).
  const bool snapshot_ok = s.snapshot_interval >= kMinSnapshotInterval && s.duration / s.snapshot_interval <= kMaxSnapshots;
  check.require(snapshots_flag ? snapshot_ok : (s.snapshot_interval == 0.0 || snapshot_ok), "outputs",
                "snapshot_interval", s.snapshot_interval,
                std::string(snapshots_flag ? "expected an interval" : "expected 0 (none) or an interval") +
                    " of at least 0.01 s and at most 100000 snapshots over --duration");
  const std::optional<std::int64_t> start = gis::parse_snapshot_start(o.snapshot_start);
  check.require(start.has_value(), "outputs", "snapshot_start", o.snapshot_start,
                "expected a date-time YYYY-MM-DDTHH:MM:SS, years 1000-9999");
  o.snapshot_start_seconds = *start;
}

// The run in one line, for the TALUS_SCENARIO metadata of every layer.
std::string scenario_text(const MudflowOptions& o) {
  const auto& s = o.settings;
  std::ostringstream text;
  text << "mudflow " << o.material << " (" << o.rheology << "), particle size " << s.particle_size << " m, adaptive "
       << (s.adaptive ? "on" : "off") << ", duration " << s.duration << " s, density " << s.mud_density
       << " kg/m3, seed " << s.seed;
  return text.str();
}

// The mud-flow layers of DESIGN.md section 3 with their band descriptions and units; erosion_depth
// only when the run has erodible material.
HazardLayers hazard_layers(const FlowLayers& layers) {
  HazardLayers out = {
      {&layers.flow_depth_max, {"flow_depth_max", "Maximum flow depth", "m"}},
      {&layers.velocity_max, {"velocity_max", "Maximum velocity", "m/s"}},
      {&layers.pressure_max, {"pressure_max", "Maximum impact pressure", "kPa"}},
      {&layers.deposit_depth, {"deposit_depth", "Deposit depth", "m"}},
      {&layers.arrival_time,
       {"arrival_time", "Arrival time of the flow", "s", gis::OverviewReduction::earliest_positive}}};
  if (layers.erosion_depth) out.push_back({&*layers.erosion_depth, {"erosion_depth", "Eroded depth", "m"}});
  return out;
}

// Wall-clock seconds since `start`.
double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// (deposited + outflow) / (released + entrained) - 1: the volume the run lost or made.
double volume_balance(const MudflowResult& result) {
  const double source = result.released_volume + result.entrained_volume;
  return source > 0.0 ? (result.deposited_volume + result.outflow_volume) / source - 1.0 : 0.0;
}

// The flow after every coarse step as columns (one array per quantity), for plotting energies.
nlohmann::ordered_json history_columns(const std::vector<MudflowHistoryPoint>& history) {
  nlohmann::ordered_json columns = {{"time_s", nlohmann::json::array()},
                                    {"kinetic_energy_j", nlohmann::json::array()},
                                    {"potential_energy_j", nlohmann::json::array()},
                                    {"internal_energy_j", nlohmann::json::array()},
                                    {"mass_kg", nlohmann::json::array()},
                                    {"flowing", nlohmann::json::array()},
                                    {"deposited", nlohmann::json::array()}};
  for (const MudflowHistoryPoint& point : history) {
    columns["time_s"].push_back(point.time);
    columns["kinetic_energy_j"].push_back(point.kinetic_energy);
    columns["potential_energy_j"].push_back(point.potential_energy);
    columns["internal_energy_j"].push_back(point.internal_energy);
    columns["mass_kg"].push_back(point.mass);
    columns["flowing"].push_back(point.flowing);
    columns["deposited"].push_back(point.deposited);
  }
  return columns;
}

// run.json: inputs with checksums, resolved parameters, counts, how the run ended, volumes.
void record_run(gis::RunRecord& record, const MudflowOptions& o, const gis::Scene& scene, const ParameterTable& table,
                const MudflowResult& result) {
  record.add_input("dem", o.inputs.dem, &scene.dem.elevation.spec());
  if (!o.inputs.lithology.empty()) record.add_input("lithology", o.inputs.lithology, nullptr);
  if (!o.inputs.vegetation.empty()) record.add_input("vegetation", o.inputs.vegetation, nullptr);
  record.add_input("release", o.inputs.release, nullptr);
  if (!o.inputs.erodible.empty()) record.add_input("erodible", o.inputs.erodible, nullptr);
  if (!o.inputs.materials.empty()) record.add_input("materials", o.inputs.materials, nullptr);
  if (!o.scenario.empty()) record.add_input("scenario", o.scenario, nullptr);
  record.set_parameters(table.values());
  record.set("seed", o.settings.seed);
  record.set("threads", result.threads);
  record.set("counts", {{"release_cells", scene.release->cell_count()},
                        {"release_points", scene.release->points.size()},
                        {"particles", {{"initial", result.initial_particles},
                                       {"peak", result.peak_particles},
                                       {"final", result.final_particles}}},
                        {"splits", result.splits},
                        {"merges", result.merges},
                        {"particle_steps", result.particle_steps},
                        {"coarse_steps", result.coarse_steps},
                        {"guard_retries", result.guard_retries},
                        {"snapshots", result.snapshots.size()}});
  record.set("end", {{"reason", to_string(result.end)},
                     {"simulated_time_s", result.simulated_time},
                     {"peak_kinetic_energy_j", result.peak_kinetic_energy}});
  record.set("conservation", {{"adaptivity_mass_change", result.adaptivity_mass_change},
                              {"adaptivity_momentum_change", result.adaptivity_momentum_change}});
  record.set("volumes_m3", {{"released", result.released_volume},
                            {"entrained", result.entrained_volume},
                            {"deposited", result.deposited_volume},
                            {"outflow", result.outflow_volume},
                            {"balance_relative", volume_balance(result)}});
  record.set("history", history_columns(result.history));
  record.set("notes", scene.notes);
  record.set("problems", scene.problems);
}

// What the run did, in three lines on stdout.
void print_summary(const MudflowResult& result, double simulate_seconds, const std::filesystem::path& out) {
  std::printf("Simulated %.1f s of flow in %.2f s (end: %s); particles %zu initial, %zu peak, %zu final; "
              "%llu particle-steps (%.0f per second, %d thread%s)\n",
              result.simulated_time, simulate_seconds, to_string(result.end), result.initial_particles,
              result.peak_particles, result.final_particles, static_cast<unsigned long long>(result.particle_steps),
              static_cast<double>(result.particle_steps) / std::max(simulate_seconds, 1e-9), result.threads,
              result.threads == 1 ? "" : "s");
  const double balance_percent = std::round(1e4 * volume_balance(result)) / 100.0 + 0.0;  // + 0.0: no "-0.00"
  std::printf("Volumes: released %.0f m3, entrained %.0f m3, deposited %.0f m3, left the DEM %.0f m3 (balance %+.2f %%)\n",
              result.released_volume, result.entrained_volume, result.deposited_volume, result.outflow_volume,
              balance_percent);
  std::printf("Layers written to %s (open the .tif files in QGIS: each has its style beside it)\n", out.c_str());
}

// Resolves and checks the parameters, reads the scene, runs the flow and writes the layer set.
int run_mudflow_command(MudflowOptions& o, ParameterTable& table, bool adaptive_given) {
  // The scenario file sets every parameter it names, except those given as flags; the material
  // preset then sets those that neither gives.
  if (!o.scenario.empty()) table.apply_scenario(o.scenario, {});
  apply_material(o, table);
  if (adaptive_given) o.settings.adaptive = parse_on_off(o.adaptive);
  validate(o, table);
  const std::optional<IntensityScheme> intensity = chosen_intensity(o.intensity, "mudflow", hazard_layers(FlowLayers{}));
  const bool project = project_wanted(o.project);
  // The output folder is checked and staged before any work (issue 18, item 3).
  gis::LayerWriter writer(o.out, {{"TALUS_PROCESS", "mud flow"}, {"TALUS_SCENARIO", scenario_text(o)}});

  const auto start = std::chrono::steady_clock::now();
  gis::RunRecord record;
  record.set_command_line(o.command_line);
  o.inputs.release_needs_depth = true;
  const gis::Scene scene = gis::load_scene(o.inputs);
  const GroundModel ground = scene.ground_model();
  const double read_seconds = seconds_since(start);
  for (const auto& note : scene.notes) std::printf("note: %s\n", note.c_str());
  for (const auto& problem : scene.problems) std::printf("problem: %s\n", problem.c_str());
  std::printf("Mud flow from %zu release cells and %zu points (%s: %s, particle size %g m, adaptive %s) ...\n",
              scene.release->cell_count(), scene.release->points.size(), o.material.c_str(), o.rheology.c_str(),
              o.settings.particle_size, o.settings.adaptive ? "on" : "off");
  std::fflush(stdout);

  const auto simulate_start = std::chrono::steady_clock::now();
  TerminalProgress progress;
  const Grid<float>* erodible = scene.erodible ? &*scene.erodible : nullptr;
  const MudflowResult result = run_mudflow(ground, *scene.release, erodible, o.settings, &progress);
  const double simulate_seconds = seconds_since(simulate_start);

  const auto write_start = std::chrono::steady_clock::now();
  const nlohmann::json intensity_entry = write_layers_with_intensity(writer, hazard_layers(result.layers), intensity);
  if (o.settings.snapshot_interval > 0.0) {
    gis::add_particle_snapshots(writer, result.snapshots, o.settings.snapshot_interval, ground.spec().crs_wkt,
                                o.snapshot_start_seconds);
  }
  record_run(record, o, scene, table, result);
  if (intensity) record.set("intensity", intensity_entry);
  record.add_timing("read_inputs", read_seconds);
  record.add_timing("simulate", simulate_seconds);
  record.add_timing("write_layers", seconds_since(write_start));
  record.write(writer.temporary_path("run.json"));
  const std::string project_line =
      write_project_if_wanted(project, writer.staging_folder(), o.out, "mudflow", o.inputs.dem, o.inputs.release);
  writer.commit();
  if (intensity) std::printf("%s\n", intensity_summary(intensity_entry).c_str());
  print_summary(result, simulate_seconds, o.out);
  if (!project_line.empty()) std::printf("%s\n", project_line.c_str());
  return 0;
}

}  // namespace

void add_mudflow_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line) {
  auto o = std::make_shared<MudflowOptions>();
  o->command_line = command_line;
  auto table = std::make_shared<ParameterTable>(parameter_table(*o));
  CLI::App* cmd = app.add_subcommand("mudflow", "Adaptive smoothed-particle mud flow and its hazard layers");
  cmd->add_option("--dem", o->inputs.dem, "DEM raster (elevations in metres)")->required();
  cmd->add_option("--release", o->inputs.release,
                  "Release depth raster (m; negative values count as depths) or polygons/points with a `depth` attribute "
                  "(m; see --depth-field and --depth)")
      ->required();
  cmd->add_option("--out", o->out, "Output folder for the layers")->required();
  cmd->add_option("--lithology", o->inputs.lithology, "Lithology class raster");
  cmd->add_option("--vegetation", o->inputs.vegetation, "Vegetation raster: class codes or deperdition coefficients (1/m)");
  cmd->add_option("--erodible", o->inputs.erodible, "Raster of erodible depth (m) the flow can entrain");
  cmd->add_option("--materials", o->inputs.materials, "Materials table (TOML); default: built-in");
  auto* material = cmd->add_option("--material", o->material,
                  "Material preset: " + MudflowMaterials::built_in().name_list() +
                      "; the scenario's keys and the other flags override its values (docs/mudflow.md)")
      ->default_val(o->material);
  cmd->add_option("--scenario", o->scenario,
                  "Scenario TOML: [run], [mud], [adaptivity], [time_steps], [contact], [rheology], [deposition], "
                  "[entrainment], [outputs] (see talus params)");
  const MudflowSettings defaults;
  auto* duration = cmd->add_option("--duration", o->settings.duration, "Longest simulated time (s)")->default_val(defaults.duration);
  auto* size = cmd->add_option("--particle-size", o->settings.particle_size, "Spacing of the finest particles (m)")
                   ->default_val(defaults.particle_size);
  auto* adaptive = cmd->add_option("--adaptive", o->adaptive, "Fission, fusion and individual time steps: on or off")
                       ->default_val("on");
  auto* rheology = cmd->add_option("--rheology", o->rheology, "Basal resistance: viscous, coulomb, voellmy or bingham")
                       ->default_val(o->rheology);
  auto* snapshots = cmd->add_option("--snapshots", o->settings.snapshot_interval,
                                    "Write particles.gpkg with the particles every SECONDS of simulated time");
  auto* seed = cmd->add_option("--seed", o->settings.seed, "Random seed")->default_val(defaults.seed);
  auto* start_time = cmd->add_option("--start-time", o->snapshot_start,
                                     "Date-time of the release on particles.gpkg's clock, YYYY-MM-DDTHH:MM:SS (default "
                                     "2000-01-01T00:00:00: the clock reads the time since release)");
  auto* depth = cmd->add_option("--depth", o->release_depth,
                                "One release depth (m) for every release cell, polygon and point: makes a 0/1 mask "
                                "or a layer without depths a release");
  auto* depth_field = cmd->add_option("--depth-field", o->depth_field,
                                      "Attribute of a vector release holding each feature's depth (m); default depth");
  auto* threads = cmd->add_option("--threads", o->settings.threads,
                                  "Threads (default: all cores). With other jobs on the machine, start Talus with "
                                  "OMP_WAIT_POLICY=passive in the environment (docs/performance.md)");
  cmd->add_option("--crs", o->inputs.crs, "CRS of the inputs: EPSG:n, WKT, or local");
  auto* intensity = cmd->add_option("--intensity", o->intensity,
                                    "Intensity classes of intensity.tif: foen-2016 (default), FILE.toml or none");
  auto* project = cmd->add_option("--project", o->project,
                                  "on (default): also write project.qgz, hillshade.tif and quicklook/*.png with QGIS; off");
  cmd->callback([o, table, &action, duration, material, size, adaptive, rheology, snapshots, seed, threads, depth,
                 depth_field, start_time, intensity, project] {
    const CLI::Option* given[] = {duration, seed,      threads,     material,    size,       adaptive,  rheology,
                                  snapshots, depth,    depth_field, start_time, intensity, project};
    static_assert(std::size(kFlags) == std::size(given));
    for (std::size_t k = 0; k < std::size(kFlags); ++k) {
      if (given[k]->count() > 0) table->pin(kFlags[k].section, kFlags[k].name);
    }
    const bool adaptive_given = adaptive->count() > 0;
    action = [o, table, adaptive_given] { return run_mudflow_command(*o, *table, adaptive_given); };
  });
}

nlohmann::json mudflow_parameters() {
  MudflowOptions defaults;
  ParameterTable table = parameter_table(defaults);
  apply_material(defaults, table);
  return table.describe();
}

nlohmann::json mudflow_materials() { return MudflowMaterials::built_in().describe(); }

}  // namespace talus::cli
