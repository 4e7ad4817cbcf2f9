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
#include "mudflow_layers.hpp"
#include "mudflow_materials.hpp"
#include "mudflow_parameters.hpp"
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

// The run in one line, for the TALUS_SCENARIO metadata of every layer.
std::string scenario_text(const MudflowOptions& o) {
  const auto& s = o.settings;
  std::ostringstream text;
  text << "mudflow " << o.material << " (" << o.rheology << "), particle size " << s.particle_size << " m, adaptive "
       << (s.adaptive ? "on" : "off") << ", duration " << s.duration << " s, density " << s.mud_density
       << " kg/m3, seed " << s.seed;
  return text.str();
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
int run_mudflow_command(MudflowOptions& o, ParameterTable& table, bool adaptive_given) {
  const auto [intensity, project] = resolve_mudflow_parameters(o, table, adaptive_given);
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
  const nlohmann::json intensity_entry = write_layers_with_intensity(writer, mudflow_hazard_layers(result.layers), intensity);
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
  auto table = std::make_shared<ParameterTable>(mudflow_parameter_table(*o));
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

}  // namespace talus::cli
