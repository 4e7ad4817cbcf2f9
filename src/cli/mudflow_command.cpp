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
#include "whole_number.hpp"
#include "run_project.hpp"
#include "terminal_progress.hpp"
#include "unfinished_flow.hpp"
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

// Particle snapshots: the most a run writes.
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
  using Range = ParameterTable::Range;  // the allowed values, in the unit (issue 18, item 1)
  ParameterTable table;
  auto& s = o.settings;
  table.add("run", "duration", "s", "longest simulated time", &s.duration, Range{0, 86400, true, false});
  table.add("run", "stop_energy_fraction", "-", "the run ends when the kinetic energy falls below this fraction of its peak",
            &s.stop_energy_fraction, Range{0, 1, false, true});
  table.add("run", "seed", "", "seed of the jitter of the particles' initial places", &s.seed);
  table.add("run", "threads", "", "threads (0: all cores); the layers do not depend on it", &s.threads,
            Range{1, kMaxThreads, false, false, 0, "all cores"});
  table.add("run", "parallel_particles", "", "loops over fewer particles than this run on one thread", &s.parallel_particles, Range{1, 1e9, false, false});
  table.add("run", "parallel_check_period", "",
            "coarse steps between timed trials of one thread against all threads for the particle loops, which then "
            "run the faster way (0: always all threads); the layers do not depend on it",
            &s.parallel_check_period, Range{3, 1e9, false, false, 0, "always all threads"});
  table.add("run", "interleaved_particles", "",
            "threads with at least this many particles to evaluate compute each particle's forces as soon as the "
            "densities they read are done, while its neighbour list is in the cache; fewer: all densities first; the "
            "layers do not depend on it",
            &s.interleaved_particles, Range{1, 1e9, false, false});
  table.add("mud", "material", "",
            "material preset that sets the rheology, its parameters and the density before the scenario's own keys: " +
                MudflowMaterials::built_in().name_list(),
            &o.material);
  table.add("mud", "density", "kg/m3", "bulk density of the mud rho0", &s.mud_density, Range{100, 3000, false, false});
  table.add("mud", "gravity", "m/s2", "gravitational acceleration", &s.gravity, Range{0.1, 30});
  table.add("mud", "particle_size", "m", "spacing of the finest particles", &s.particle_size, Range{0.05, 100, false, false});
  table.add("mud", "release_thickness", "",
            "how a release depth is measured: normal (to the ground, the thin-layer convention) or vertical",
            &o.release_thickness);
  table.add("mud", "release_depth", "m",
            "one release depth for every release cell, polygon and point, whatever the release file holds (0: the "
            "file's depths)",
            &o.release_depth, Range{0.01, gis::kMaxReleaseDepth, false, false, 0, "the release file's depths"});
  table.add("mud", "depth_field", "", "the attribute of a vector release that holds each feature's depth (m)",
            &o.depth_field);
  table.add("adaptivity", "adaptive", "", "particle fission and fusion and individual time steps (paper 4.2)", &s.adaptive);
  table.add("adaptivity", "coarse_levels", "",
            "particle sizes are particle_size x 2^k, k = 0..coarse_levels; the release uses the coarsest", &s.coarse_levels, Range{0, 8, false, false});
  table.add("adaptivity", "split_threshold", "-", "a particle splits when its size x |grad P| / P exceeds this",
            &s.split_threshold, Range{0, 100, true, false});
  table.add("adaptivity", "merge_threshold", "-", "a calm group merges when each member's size x |grad P| / P is below this",
            &s.merge_threshold, Range{0, 100, false, true});
  table.add("adaptivity", "merge_speed", "m/s", "and its members' velocities differ by less than this", &s.merge_speed, Range{0, 100, false, false});
  table.add("time_steps", "courant", "-",
            "C in dt = C min(s / (c + w), sqrt(s / |a|)), w the fastest closing speed of a neighbour", &s.courant, Range{0, 1, true, false});
  table.add("time_steps", "cells_per_step", "-", "a particle's step crosses at most this many DEM cells",
            &s.cells_per_step, Range{0, 10, true, false});
  table.add("time_steps", "longest_step", "s", "step of level 0; level k steps are longest_step / 2^k", &s.longest_step, Range{0.001, 10, false, false});
  table.add("time_steps", "deepest_level", "", "deepest step level", &s.deepest_level, Range{0, 30, false, false});
  table.add("time_steps", "guard", "", "detect blown-up steps and retry them with halved steps", &s.guard);
  table.add("time_steps", "max_retries", "", "step halvings before a run fails with exit code 3", &s.max_retries, Range{0, 20, false, false});
  table.add("time_steps", "unguarded_step", "s", "> 0: one global step that ignores the Courant condition (tests of the guard)",
            &s.unguarded_step, Range{1e-4, 10, false, false, 0, "off"});
  table.add("contact", "curvature", "",
            "the basal normal stress includes the centripetal term rho0 h u^2 kappa of the ground's curvature", &s.curvature);
  table.add("contact", "curvature_span", "m",
            "kappa is measured between the ground normals this far apart along the velocity (at least one DEM cell and "
            "the particle's spacing)",
            &s.curvature_span, Range{0, 1000, false, false});
  auto& r = s.rheology;
  table.add("rheology", "rheology", "", "basal resistance: viscous, coulomb, voellmy or bingham", &o.rheology);
  table.add("rheology", "friction", "-", "Coulomb friction coefficient mu of the basal resistance (coulomb, voellmy)",
            &r.friction, Range{0, 1, false, false});
  table.retire("rheology", "friction_factor",
               "no longer used: give [rheology] friction, the friction coefficient mu itself (0-1); the lithology no "
               "longer sets the mud's friction");
  table.add("rheology", "turbulence", "m/s2", "turbulence coefficient xi of Voellmy", &r.turbulence, Range{0, 1e6, true, false});
  table.add("rheology", "viscosity", "Pa s", "dynamic viscosity eta (viscous and Bingham)", &r.viscosity, Range{0, 1e9, false, false});
  table.add("rheology", "yield_stress", "Pa", "yield stress tau_y of Bingham", &r.yield_stress, Range{0, 1e7, false, false});
  table.add("rheology", "internal_viscosity", "m2/s", "kinematic viscosity of the internal friction between particles",
            &r.internal_viscosity, Range{0, 1e4, false, false});
  table.add("deposition", "stop_speed", "m/s", "mud slower than this for stop_duration, and held by the bed, deposits",
            &s.stop_speed, Range{0, 100, false, false});
  table.add("deposition", "stop_duration", "s", "how long the mud must stay slower than stop_speed", &s.stop_duration, Range{0, 86400, false, false});
  table.add("entrainment", "rate", "1/m", "entrainment rate E: the bed erodes at E h |u| (m/s) where erodible material lies",
            &s.entrainment_rate, Range{0, 10, false, false});
  table.add("outputs", "arrival_depth", "m", "a cell is reached when its flow depth first exceeds this", &s.arrival_depth, Range{0, 100, true, false});
  table.add("outputs", "map_interval", "s", "flow depth, velocity and pressure maxima are sampled this often",
            &s.map_interval, Range{0.01, 3600, false, false});
  table.add("outputs", "snapshot_interval", "s", "> 0: particles.gpkg holds the particles this often", &s.snapshot_interval, Range{0.01, 86400, false, false, 0, "none"});
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
  table.require(materials.contains(o.material), "mud", "material", o.material,
                "expected one of " + materials.name_list());
  materials.apply(o.material, table);
}

// Every parameter within its range (the table's data, docs/mudflow.md), then the choices and the
// rules between values that a range cannot say.
void validate(MudflowOptions& o, const ParameterTable& table) {
  table.check_ranges();
  const auto& s = o.settings;
  const std::string rheology = o.rheology;
  table.require(rheology == "viscous" || rheology == "coulomb" || rheology == "voellmy" || rheology == "bingham", "rheology",
                "rheology", rheology, "use viscous, coulomb, voellmy or bingham");
  o.settings.rheology.rheology = parse_rheology(rheology);
  table.require(o.release_thickness == "normal" || o.release_thickness == "vertical", "mud", "release_thickness",
                o.release_thickness, "use normal or vertical");
  o.settings.release_thickness = parse_release_thickness(o.release_thickness);
  table.require(!o.depth_field.empty(), "mud", "depth_field", o.depth_field, "expected an attribute name");
  table.require(o.release_depth == 0.0 || o.depth_field == "depth", "mud", "depth_field", o.depth_field,
                "give either a depth attribute or one release depth, not both");
  o.inputs.release_depth.field = o.depth_field;
  if (o.release_depth > 0.0) o.inputs.release_depth.uniform = o.release_depth;
  table.require(s.merge_threshold < s.split_threshold, "adaptivity", "merge_threshold", number_text(s.merge_threshold),
                "expected a ratio below split_threshold " + number_text(s.split_threshold));
  // At most kMaxSnapshots in the run, so that a tiny interval is refused now, not after the whole
  // flow when particles.gpkg is written (issue 18).
  table.require(s.snapshot_interval == 0.0 || s.duration / s.snapshot_interval <= kMaxSnapshots, "outputs",
                "snapshot_interval", number_text(s.snapshot_interval), "expected at most 100000 snapshots over --duration");
  const bool snapshots_flag = table.given_on_command_line("outputs", "snapshot_interval");
  table.require(!snapshots_flag || s.snapshot_interval > 0.0, "outputs", "snapshot_interval",
                number_text(s.snapshot_interval), "expected an interval of at least 0.01 s");
  const std::optional<std::int64_t> start = gis::parse_snapshot_start(o.snapshot_start);
  table.require(start.has_value(), "outputs", "snapshot_start", o.snapshot_start,
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
  std::vector<std::string> problems = scene.problems;
  const std::vector<std::string> unfinished = unfinished_flow_problems(result, o.settings);
  problems.insert(problems.end(), unfinished.begin(), unfinished.end());
  record.set("problems", problems);
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
// What a run chose besides its numbers: the intensity classes and whether it writes a project.
struct RunChoices {
  std::optional<IntensityScheme> intensity;
  bool project = true;
};

// The scenario file, the material preset and the flags resolved into `o`, every parameter
// checked: what a run does before it reads any input.
RunChoices resolve_parameters(MudflowOptions& o, ParameterTable& table, bool adaptive_given) {
  // The scenario file sets every parameter it names, except those given as flags; the material
  // preset then sets those that neither gives.
  if (!o.scenario.empty()) table.apply_scenario(o.scenario, {});
  apply_material(o, table);
  if (adaptive_given) o.settings.adaptive = parse_on_off(o.adaptive);
  validate(o, table);
  RunChoices choices;
  choices.intensity = chosen_intensity(o.intensity, "mudflow", hazard_layers(FlowLayers{}));
  choices.project = project_wanted(o.project);
  return choices;
}

int run_mudflow_command(MudflowOptions& o, ParameterTable& table, bool adaptive_given) {
  const auto [intensity, project] = resolve_parameters(o, table, adaptive_given);
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
  for (const auto& problem : unfinished_flow_problems(result, o.settings)) std::printf("problem: %s\n", problem.c_str());
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
  auto* seed = cmd->add_option("--seed", o->settings.seed, "Random seed")->default_val(defaults.seed)->check(whole_number());
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
      if (given[k]->count() > 0) table->pin(kFlags[k].section, kFlags[k].name, kFlags[k].option);
    }
    const bool adaptive_given = adaptive->count() > 0;
    action = [o, table, adaptive_given] { return run_mudflow_command(*o, *table, adaptive_given); };
  });
}

void check_mudflow_scenario(const std::filesystem::path& scenario) {
  MudflowOptions o;
  o.scenario = scenario;
  ParameterTable table = parameter_table(o);
  resolve_parameters(o, table, false);
}

nlohmann::json mudflow_parameters() {
  MudflowOptions defaults;
  ParameterTable table = parameter_table(defaults);
  apply_material(defaults, table);
  return table.describe();
}

nlohmann::json mudflow_materials() { return MudflowMaterials::built_in().describe(); }

}  // namespace talus::cli
