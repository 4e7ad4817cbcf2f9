// The work of `talus mudflow` as one library call (docs/architecture.md section 3, issue 5; issue 19): the
// adaptive smoothed-particle mud flow of paper section 4 on the scene, every mud-flow layer,
// optional particle snapshots and run.json, committed as one set.
#include "mudflow_job.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <sstream>

#include "intensity_layer.hpp"
#include "mudflow_layers.hpp"
#include "mudflow_window.hpp"
#include "release_convention.hpp"
#include "run_project.hpp"
#include "unfinished_flow.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/layer_writer.hpp"
#include "talus/gis/particle_snapshot_writer.hpp"
#include "talus/gis/run_record.hpp"
#include "talus/gis/scene.hpp"
#include "talus/mudflow/mudflow_simulation.hpp"

namespace talus::cli {
namespace {

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
                const MudflowResult& result, const std::vector<std::string>& halo_problems) {
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
                            {"halo_outflow", result.halo_outflow_volume},
                            {"balance_relative", volume_balance(result)}});
  record.set("history", history_columns(result.history));
  record.set("notes", scene.notes);
  std::vector<std::string> problems = scene.problems;
  const std::vector<std::string> unfinished = unfinished_flow_problems(result, o.settings);
  problems.insert(problems.end(), unfinished.begin(), unfinished.end());
  problems.insert(problems.end(), halo_problems.begin(), halo_problems.end());
  record.set("problems", problems);
}

// What the run did, in three lines.
void say_summary(const MudflowResult& result, double simulate_seconds, const std::filesystem::path& out,
                 const JobOutput& output) {
  output.say(printf_text("Simulated %.1f s of flow in %.2f s (end: %s); particles %zu initial, %zu peak, %zu final; "
              "%llu particle-steps (%.0f per second, %d thread%s)",
              result.simulated_time, simulate_seconds, to_string(result.end), result.initial_particles,
              result.peak_particles, result.final_particles, static_cast<unsigned long long>(result.particle_steps),
              static_cast<double>(result.particle_steps) / std::max(simulate_seconds, 1e-9), result.threads,
              result.threads == 1 ? "" : "s"));
  const double balance_percent = std::round(1e4 * volume_balance(result)) / 100.0 + 0.0;  // + 0.0: no "-0.00"
  const std::string window_part =
      result.halo_outflow_volume > 0.0 ? printf_text(" (%.0f m3 across its window's halo)", result.halo_outflow_volume) : "";
  output.say(printf_text("Volumes: released %.0f m3, entrained %.0f m3, deposited %.0f m3, left the DEM %.0f m3%s (balance %+.2f %%)",
              result.released_volume, result.entrained_volume, result.deposited_volume, result.outflow_volume,
              window_part.c_str(), balance_percent));
  output.say("Layers written to " + out.string() + " (open the .tif files in QGIS: each has its style beside it)");
}

}  // namespace

void mudflow_job(MudflowOptions& o, ParameterTable& table, bool adaptive_given, const JobOutput& output) {
  const auto [intensity, project] = resolve_mudflow_parameters(o, table, adaptive_given);
  // The output folder is checked and staged before any work (issue 18, item 3).
  gis::LayerWriter writer(o.out, {{"TALUS_PROCESS", "mud flow"}, {"TALUS_SCENARIO", scenario_text(o)}});

  const auto start = std::chrono::steady_clock::now();
  gis::RunRecord record;
  record.set_command_line(o.command_line);
  o.inputs.release_needs_depth = true;
  gis::Scene scene = gis::load_region(o.inputs);
  // Margin around the halo: ten of the coarsest particles and the curvature span.
  const double margin = 10.0 * o.settings.particle_size * std::ldexp(1.0, o.settings.coarse_levels) +
                        o.settings.curvature_span;
  const MudflowWindow window = plan_mudflow_window(scene, o.tiles, margin);
  std::optional<gis::Scene> tile;
  std::optional<ReleaseSet> window_release;
  if (window.window) {
    tile.emplace(gis::load_tile(scene, *window.window));
    scene.notes.insert(scene.notes.end(), tile->notes.begin(), tile->notes.end());
    scene.problems.insert(scene.problems.end(), tile->problems.begin(), tile->problems.end());
    window_release.emplace(scene.release->window(*window.window));
    o.settings.window_edge = window.halo_edge;
  } else {
    gis::add_ground_maps(scene);
  }
  const gis::Scene& ground_scene = tile ? *tile : scene;
  const GroundModel ground = ground_scene.ground_model();
  const ReleaseSet& release = window_release ? *window_release : *scene.release;
  const ReleaseConvention convention = release_convention(ground, release, o.release_thickness_choice);
  o.settings.release_thickness = convention.thickness;
  const double read_seconds = seconds_since(start);
  for (const auto& note : scene.notes) output.say("note: " + note);
  for (const auto& problem : scene.problems) output.say("problem: " + problem);
  if (window.window) {
    output.say(printf_text("Window: %d x %d cells around the release with a halo of %g m, for --memory %.3g GB",
                           window.window->width, window.window->height, window.halo, window.memory_bytes / 1e9));
  }
  output.say(printf_text("Mud flow from %zu release cells and %zu points (%s: %s, particle size %g m, adaptive %s) ...",
              scene.release->cell_count(), scene.release->points.size(), o.material.c_str(), o.rheology.c_str(),
              o.settings.particle_size, o.settings.adaptive ? "on" : "off"));
  output.say("Release: " + release_convention_text(convention));

  const auto simulate_start = std::chrono::steady_clock::now();
  const Grid<float>* erodible = ground_scene.erodible ? &*ground_scene.erodible : nullptr;
  MudflowResult result = run_mudflow(ground, release, erodible, o.settings, &output.progress);
  if (window.window) result.layers = whole_region_layers(result.layers, scene.dem.elevation);
  const double simulate_seconds = seconds_since(simulate_start);
  const std::vector<std::string> halo_problems = halo_outflow_problems(result, window.halo);

  const auto write_start = std::chrono::steady_clock::now();
  const nlohmann::json intensity_entry = write_layers_with_intensity(writer, mudflow_hazard_layers(result.layers), intensity);
  if (o.settings.snapshot_interval > 0.0) {
    gis::add_particle_snapshots(writer, result.snapshots, o.settings.snapshot_interval, ground.spec().crs_wkt,
                                o.snapshot_start_seconds);
  }
  record_run(record, o, scene, table, result, halo_problems);
  record.set("release", release_convention_record(convention));
  record.set("tiles", window_record(window));
  if (intensity) record.set("intensity", intensity_entry);
  record.add_timing("read_inputs", read_seconds);
  record.add_timing("simulate", simulate_seconds);
  record.add_timing("write_layers", seconds_since(write_start));
  record.write(writer.temporary_path("run.json"));
  const std::string project_line =
      write_project_if_wanted(project, writer.staging_folder(), o.out, "mudflow", o.inputs.dem, o.inputs.release);
  writer.commit();
  if (intensity) output.say(intensity_summary(intensity_entry));
  say_summary(result, simulate_seconds, o.out, output);
  for (const auto& problem : unfinished_flow_problems(result, o.settings)) output.say("problem: " + problem);
  for (const auto& problem : halo_problems) output.say("problem: " + problem);
  if (!project_line.empty()) output.say(project_line);
}


}  // namespace talus::cli
