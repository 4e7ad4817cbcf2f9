// `talus rockfall` (DESIGN.md section 3, issue 3): stochastic rock-fall trajectories on the
// user's scene and every rock-fall layer, trajectories.gpkg and run.json.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <sstream>

#include "commands.hpp"
#include "envelope_convergence_report.hpp"
#include "intensity_layer.hpp"
#include "number_list.hpp"
#include "parameter_table.hpp"
#include "whole_number.hpp"
#include "run_project.hpp"
#include "terminal_progress.hpp"
#include "truncated_trajectories.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/layer_writer.hpp"
#include "talus/gis/run_record.hpp"
#include "talus/gis/scene.hpp"
#include "talus/gis/trajectory_writer.hpp"
#include "talus/rockfall/fast_bounce.hpp"
#include "talus/rockfall/full_model.hpp"
#include "talus/rockfall/monte_carlo.hpp"

namespace talus::cli {
namespace {

struct RockfallOptions {
  gis::SceneInputs inputs;
  std::filesystem::path out;
  std::filesystem::path scenario;
  std::string mode = "fast";
  std::string block_shape = "sphere";
  std::string block_size = "1";
  CountOrAuto runs{true, 0};   // into settings.runs_per_source and settings.auto_runs
  std::string runs_flag;       // --runs as given
  std::string project = "on";  // --project on|off, [outputs] project
  std::string intensity = kDefaultIntensity;  // --intensity, [outputs] intensity
  RockfallSettings settings;
  FastBounceParameters fast;
  FullModelParameters full;
  double fracture_strength = FullModelParameters{}.fracture_strength / 1000.0;  // kN, into full.fracture_strength (N)
  std::vector<std::string> command_line;
};

BlockShape parse_shape(const std::string& text) {
  if (text == "sphere") return BlockShape::sphere;
  if (text == "ellipsoid") return BlockShape::ellipsoid;
  if (text == "box") return BlockShape::box;
  throw InputError("--block-shape " + text + ": use sphere, ellipsoid or box");
}

// "D" (a sphere's diameter, or all three axes) or "A,B,C" (m).
Eigen::Vector3d parse_size(const std::string& text) {
  std::vector<double> values = parse_number_list("--block-size", text);
  if (values.size() == 1) values.assign(3, values[0]);
  if (values.size() != 3) throw InputError("--block-size " + text + ": give D or A,B,C in metres");
  for (double v : values) {
    if (!(v > kMinRockAxis && v < kMaxRockAxis)) {
      throw InputError("--block-size " + text + ": axes must lie between 0.01 and 100 m");
    }
  }
  return {values[0], values[1], values[2]};
}

ParameterTable parameter_table(RockfallOptions& o) {
  using Range = ParameterTable::Range;  // the allowed values, in the unit (issue 18, item 1)
  ParameterTable table;
  table.add("run", "mode", "", "trajectory model: fast (impulse bounces) or full (piston carpet)", &o.mode);
  table.add("run", "runs", "runs",
            "trajectories per release cell or point (1 or more), or \"auto\": per source, doubled from min_runs until "
            "its maps change by less than convergence_tolerance (docs/hazard-statistics.md, Convergence)",
            &o.runs, Range{1, 1e+09, false, false});
  auto& c = o.settings.convergence;
  table.add("run", "convergence_tolerance", "-",
            "converged: the reach probability and the energy per run change by less than this (L1, relative) over the "
            "last doubling of the runs (0-1, exclusive)",
            &c.tolerance, Range{0, 1, true, true});
  table.add("run", "min_runs", "runs", "runs = \"auto\": runs per source before the first convergence test (2 or more)",
            &c.min_runs, Range{2, 1e+09, false, false});
  table.add("run", "max_runs", "runs",
            "runs = \"auto\": most runs per source (min_runs or more); a source stops at the last doubling of min_runs "
            "not above it",
            &c.max_runs, Range{2, 1e+09, false, false});
  table.add("run", "seed", "", "seed of the counter-based random numbers", &o.settings.seed);
  table.add("run", "threads", "", "threads (0: all cores); the layers do not depend on it", &o.settings.threads,
            Range{1, kMaxThreads, false, false, 0, "all cores"});
  table.add("run", "saved_trajectories", "", "at most this many lines in trajectories.gpkg", &o.settings.saved_trajectories, Range{0, 1e+07, false, false});
  table.add("outputs", "project", "",
            "on: also write project.qgz, hillshade.tif and quicklook/*.png with QGIS (python3-qgis); off: not", &o.project);
  table.add("outputs", "intensity", "",
            "intensity classes of intensity.tif: a built-in guideline (foen-2016), a guideline file FILE.toml, or none",
            &o.intensity);
  table.add("rock", "shape", "", "sphere, ellipsoid or box", &o.block_shape);
  table.add("rock", "size", "m", "diameter, or axes A,B,C", &o.block_size);
  table.add("rock", "density", "kg/m3", "rock density", &o.settings.rock.density,
            Range{kMinRockDensity, kMaxRockDensity, false, false});
  table.add("rock", "fracture_parts", "",
            "pre-fractured block (full mode): 1 intact, 2 halves across the longest axis, 4 also across the second, 8 octants",
            &o.full.fracture_parts, Range{1, 8, false, false});
  table.add("rock", "fracture_strength", "kN", "force beyond which a bond between two parts of the block breaks",
            &o.fracture_strength, Range{0, 1e+09, true, false});
  auto& s = o.settings.stochastic;
  table.add("stochastic", "release_jitter", "-", "release point uniform over this fraction of its cell", &s.release_jitter, Range{0, 1, false, false});
  table.add("stochastic", "release_height", "m", "start height of the rock's lowest point above the ground", &s.release_height, Range{0, 1000, false, false});
  table.add("stochastic", "size_variation", "-", "axes scaled by U(1-v, 1+v)", &s.size_variation, Range{0, 0.9, false, false});
  table.add("stochastic", "density_variation", "-", "density scaled by U(1-v, 1+v)", &s.density_variation, Range{0, 0.9, false, false});
  table.add("stochastic", "restitution_variation", "-", "restitutions scaled by U(1-v, 1+v)", &s.restitution_variation, Range{0, 0.9, false, false});
  table.add("stochastic", "friction_variation", "-", "friction scaled by U(1-v, 1+v)", &s.friction_variation, Range{0, 0.9, false, false});
  table.add("stochastic", "noise_frequency", "-", "Perlin base frequency times the rock diameter", &s.noise_frequency, Range{0, 100, false, false});
  table.add("stochastic", "noise_octaves", "", "Perlin octaves", &s.noise_octaves, Range{0, 16, false, false});
  table.add("stochastic", "noise_reference_size", "m",
            "rocks at least this large see the materials' noise amplitudes; a smaller rock sees them scaled by its size / this",
            &s.noise_reference_size, Range{0, 100, true, false});
  auto& f = o.fast;
  table.add("fast_bounce", "gravity", "m/s2", "gravitational acceleration", &f.gravity, Range{0.1, 100});
  table.add("fast_bounce", "air_density", "kg/m3", "air density for drag", &f.air_density, Range{0, 10, false, false});
  table.add("fast_bounce", "drag_coefficient", "-", "Cx of paper 3.2 (0 disables drag)", &f.drag_coefficient, Range{0, 10, false, false});
  table.add("fast_bounce", "max_time", "s", "simulated time limit per trajectory", &f.max_time, Range{0, 100000, true, false});
  table.add("fast_bounce", "stop_speed", "m/s", "speed under which a rock held by friction stops", &f.stop_speed, Range{1e-4, 10});
  table.add("fast_bounce", "contact_speed", "m/s", "touchdown or rebound normal speed under which the rock rolls or slides",
            &f.contact_speed, Range{1e-3, 100});
  table.add("fast_bounce", "max_step_length", "m", "longest flight path between two ground checks", &f.max_step_length, Range{1e-3, 100});
  table.add("fast_bounce", "sample_spacing", "m", "longest path between two recorded samples", &f.sample_spacing, Range{0.01, 1000});
  table.add("fast_bounce", "contact_time_step", "s", "longest step of the rolling/sliding phase", &f.contact_time_step, Range{1e-4, 10});
  table.add("fast_bounce", "contact_tolerance", "m", "ground drop or rise within a contact step that ends it (take-off, shorter step)",
            &f.contact_tolerance, Range{1e-4, 10});
  auto& m = o.full;
  table.add("full", "gravity", "m/s2", "gravitational acceleration", &m.gravity, Range{0.1, 100});
  table.add("full", "air_density", "kg/m3", "air density for drag", &m.air_density, Range{0, 10, false, false});
  table.add("full", "drag_coefficient", "-", "Cx of paper 3.2 (0 disables drag)", &m.drag_coefficient, Range{0, 10, false, false});
  table.add("full", "max_time", "s", "simulated time limit per trajectory", &m.max_time, Range{0, 100000, true, false});
  table.add("full", "stop_speed", "m/s", "mean speed of centre and rim over stop_duration under which a rock in contact is at rest",
            &m.stop_speed, Range{1e-4, 10});
  table.add("full", "stop_duration", "s", "window over which the mean speed is compared with stop_speed", &m.stop_duration, Range{0, 100, true, false});
  table.add("full", "carpet_spacing", "-", "piston spacing as a fraction of the rock's diameter", &m.carpet_spacing, Range{0.01, 1});
  table.add("full", "time_step_factor", "-", "contact step as a fraction of the stiffest contact period", &m.time_step_factor, Range{1e-3, 1});
  table.add("full", "max_flight_step", "s", "longest time step in flight", &m.max_flight_step, Range{1e-5, 10});
  table.add("full", "sample_spacing", "m", "longest path between two recorded samples", &m.sample_spacing, Range{0.01, 1000});
  table.add("full", "friction_slip_speed", "m/s", "slip speed below which Coulomb friction is regularised", &m.friction_slip_speed, Range{1e-4, 10});
  table.add("full", "rolling_resistance", "-", "multiplier of the lithology's rolling friction (0: pure rolling)",
            &m.rolling_resistance, Range{0, 100, false, false});
  table.add("full", "guard", "", "detect blown-up steps and retry them with smaller steps", &m.guard);
  table.add("full", "max_retries", "", "step halvings before a run fails with exit code 3", &m.max_retries, Range{0, 60, false, false});
  table.add("full", "approach_fraction", "-", "per step, a piston top may be approached by this fraction of the spacing beyond its gap",
            &m.approach_fraction, Range{0.01, 1});
  table.add("full", "fresh_contact_pistons", "", "a coming contact's stiffness counts this many pistons at k3", &m.fresh_contact_pistons, Range{0, 1e+06, false, false});
  table.add("full", "grazing_cosine", "-",
            "floor of |normal . piston axis| in the piston force; a fragment's piston compresses at most its depth in the rock / this",
            &m.grazing_cosine, Range{0, 1, true, false});
  table.add("full", "guard_tolerance", "-", "energy growth per step, relative to kinetic + elastic + m g spacing, that counts as blow-up",
            &m.guard_tolerance, Range{0, 1000, true, false});
  table.add("full", "carpet_margin", "m", "extra width of the piston carpet around the rock's footprint", &m.carpet_margin, Range{0, 100, false, false});
  table.add("full", "surface_samples", "", "surface samples of the rock (air drag integral)", &m.surface_samples, Range{1, 1e+06, false, false});
  table.add("full", "mass_resolution", "", "cells per axis of the mass and inertia integration", &m.mass_resolution, Range{1, 1000, false, false});
  return table;
}

std::string scenario_text(const RockfallOptions& o) {
  std::ostringstream text;
  text << "rockfall " << o.mode << ", ";
  if (o.settings.auto_runs) {
    text << "runs per source until converged within " << o.settings.convergence.tolerance;
  } else {
    text << o.settings.runs_per_source << " runs per source";
  }
  text << ", seed " << o.settings.seed
       << ", " << o.block_shape << " " << o.block_size << " m, " << o.settings.rock.density << " kg/m3";
  return text.str();
}

// The run's hazard layers with their file names, descriptions and units (DESIGN.md section 3).
HazardLayers hazard_layers(const RockfallLayers& layers) {
  return {{&layers.reach_probability, {"reach_probability", "Reach probability per contributing source", ""}},
          {&layers.passages, {"passages", "Number of passages", ""}},
          {&layers.source_count, {"source_count", "Number of release sources reaching the cell", ""}},
          {&layers.deposits, {"deposits", "Number of deposited rocks", ""}},
          {&layers.energy_max, {"energy_max", "Maximum kinetic energy", "kJ"}},
          {&layers.energy_p95, {"energy_p95", "95th percentile of kinetic energy over passages", "kJ"}},
          {&layers.jump_height_p95, {"jump_height_p95", "95th percentile of jump height over passages", "m"}},
          {&layers.velocity_max, {"velocity_max", "Maximum velocity", "m/s"}},
          {&layers.energy_loss_friction,
           {"energy_loss_friction", "Energy lost by friction, mean per simulated rock", "kJ"}},
          {&layers.energy_loss_deformation,
           {"energy_loss_deformation", "Energy lost by ground deformation, mean per simulated rock", "kJ"}}};
}

// Median, 95th percentile (nearest rank) and maximum of the runs' horizontal path lengths (m).
nlohmann::json runout_summary(std::vector<double> runouts) {
  if (runouts.empty()) return {{"median_m", 0.0}, {"p95_m", 0.0}, {"max_m", 0.0}};
  std::sort(runouts.begin(), runouts.end());
  const auto rank = [&](double q) {
    const auto k = static_cast<std::size_t>(std::ceil(q * static_cast<double>(runouts.size())));
    return runouts[std::clamp<std::size_t>(k, 1, runouts.size()) - 1];
  };
  const std::size_t n = runouts.size();
  const double median = n % 2 == 1 ? runouts[n / 2] : 0.5 * (runouts[n / 2 - 1] + runouts[n / 2]);
  return {{"median_m", median}, {"p95_m", rank(0.95)}, {"max_m", runouts.back()}};
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The trajectory model the run uses: fast bounce or the full piston-carpet model.
std::unique_ptr<TrajectoryModel> trajectory_model(const RockfallOptions& o) {
  if (o.mode == "fast") return std::make_unique<FastBounce>(o.fast);
  return std::make_unique<FullModel>(o.full);
}

// The command line that reruns one trajectory alone: this run's, with --only-source and
// --only-run set to it (docs/rockfall-full.md, section 5).
std::string single_trajectory_command(const std::vector<std::string>& command_line, std::uint64_t source,
                                      std::uint64_t run) {
  std::string text;
  for (std::size_t i = 0; i < command_line.size(); ++i) {
    const std::string& word = command_line[i];
    if (word == "--only-source" || word == "--only-run") {
      ++i;
      continue;
    }
    if (word.rfind("--only-source=", 0) == 0 || word.rfind("--only-run=", 0) == 0) continue;
    const bool plain = !word.empty() && word.find_first_of(" \t'\"$\\") == std::string::npos;
    text += (text.empty() ? "" : " ") + (plain ? word : "'" + word + "'");
  }
  return text + " --only-source " + std::to_string(source) + " --only-run " + std::to_string(run);
}

// run_rockfall, with a failing trajectory's error extended by the command that reproduces it.
RockfallResult run_trajectories(const GroundModel& ground, const std::vector<ReleaseSource>& sources,
                                const TrajectoryModel& model, const RockfallOptions& o, TerminalProgress& progress) {
  try {
    return run_rockfall(ground, sources, model, o.settings, &progress);
  } catch (const TrajectoryFailure& failure) {
    throw NumericalFailure(std::string(failure.what()) + "; nothing was written; to rerun that trajectory alone: " +
                           single_trajectory_command(o.command_line, failure.source, failure.run));
  }
}

// --runs (or [run] runs) into the settings, and the convergence parameters checked: a tolerance
// in (0, 1); with auto, min_runs >= 2 and max_runs >= min_runs; --only-run below the runs.
void validate_runs(RockfallOptions& o) {
  if (!o.runs_flag.empty()) o.runs = parse_count_or_auto("--runs", o.runs_flag);
  RockfallSettings& s = o.settings;
  s.auto_runs = o.runs.automatic;
  if (!s.auto_runs) s.runs_per_source = o.runs.count;
  if (!s.auto_runs && s.runs_per_source == 0) throw InputError("--runs 0: at least one run per source");
  const ConvergenceParameters& c = s.convergence;
  if (!(c.tolerance > 0.0 && c.tolerance < 1.0)) {
    throw InputError("[run] convergence_tolerance " + std::to_string(c.tolerance) + ": expected a fraction between 0 and 1");
  }
  if (s.auto_runs && c.min_runs < 2) {
    throw InputError("[run] min_runs " + std::to_string(c.min_runs) +
                     ": --runs auto needs at least 2 runs per source before its first test");
  }
  if (s.auto_runs && c.max_runs < c.min_runs) {
    throw InputError("[run] max_runs " + std::to_string(c.max_runs) + ": below [run] min_runs " +
                     std::to_string(c.min_runs) + ", the first batch of --runs auto");
  }
  const std::uint64_t runs = s.auto_runs ? auto_run_limit(c) : s.runs_per_source;
  if (s.only_run && *s.only_run >= runs) {
    throw InputError("--only-run " + std::to_string(*s.only_run) + ": runs are numbered 0 to " +
                     (s.auto_runs ? "the auto limit - 1 (" : "--runs - 1 (") + std::to_string(runs - 1) + ")");
  }
}

// What a run chose besides its numbers: the intensity classes and whether it writes a project.
struct RunChoices {
  std::optional<IntensityScheme> intensity;
  bool project = true;
};

// The scenario file and the flags resolved into `o`, every parameter checked: what a run does
// before it reads any input.
RunChoices resolve_parameters(RockfallOptions& o, ParameterTable& table) {
  // The scenario file sets every parameter it names, except those given as flags (pinned).
  if (!o.scenario.empty()) table.apply_scenario(o.scenario, {});
  if (o.mode != "fast" && o.mode != "full") throw InputError("--mode " + o.mode + ": use fast or full");
  o.settings.rock.shape = parse_shape(o.block_shape);
  o.settings.rock.axes = parse_size(o.block_size);
  if (o.settings.rock.shape == BlockShape::sphere && o.settings.rock.axes.maxCoeff() != o.settings.rock.axes.minCoeff()) {
    throw InputError("--block-size " + o.block_size + ": a sphere has one diameter; use --block-shape ellipsoid or box");
  }
  validate_runs(o);
  // Every other number against its range, naming the flag or scenario key that gave it.
  table.check_ranges();
  const int parts = o.full.fracture_parts;
  if (parts != 1 && parts != 2 && parts != 4 && parts != 8) {
    throw InputError("[rock] fracture_parts " + std::to_string(parts) + ": use 1 (intact), 2, 4 or 8");
  }
  if (parts > 1 && o.mode != "full") {
    throw InputError("[rock] fracture_parts " + std::to_string(parts) +
                     ": pre-fractured blocks need --mode full (fast mode moves intact rocks only)");
  }
  if (!(o.fracture_strength > 0.0 && std::isfinite(o.fracture_strength))) {
    throw InputError("[rock] fracture_strength " + std::to_string(o.fracture_strength) + ": expected a force > 0 kN");
  }
  o.full.fracture_strength = 1000.0 * o.fracture_strength;
  RunChoices choices;
  choices.intensity = chosen_intensity(o.intensity, "rockfall", hazard_layers(RockfallLayers{}));
  choices.project = project_wanted(o.project);
  return choices;
}

int run_rockfall_command(RockfallOptions& o, ParameterTable& table) {
  const auto [intensity, project] = resolve_parameters(o, table);
  // The output folder is checked and staged before any work (issue 18, item 3).
  gis::LayerWriter writer(o.out, {{"TALUS_PROCESS", "rock fall"}, {"TALUS_SCENARIO", scenario_text(o)}});

  const auto start = std::chrono::steady_clock::now();
  gis::RunRecord record;
  record.set_command_line(o.command_line);
  o.inputs.run_rock = o.settings.rock;
  const gis::Scene scene = gis::load_scene(o.inputs);
  const GroundModel ground = scene.ground_model();
  const std::vector<ReleaseSource> sources = release_sources(*scene.release);
  const std::optional<std::uint64_t>& only_source = o.settings.only_source;
  if (only_source && *only_source >= sources.size()) {
    throw InputError("--only-source " + std::to_string(*only_source) + ": sources are numbered 0 to " +
                     std::to_string(sources.size() - 1) + " (" + o.inputs.release.string() + ")");
  }
  const double read_seconds = seconds_since(start);
  for (const auto& note : scene.notes) std::printf("note: %s\n", note.c_str());
  for (const auto& problem : scene.problems) std::printf("problem: %s\n", problem.c_str());
  if (o.settings.auto_runs) {
    std::printf("Simulating %zu sources x %llu to %llu runs until converged (--runs auto, %s mode) ...\n",
                sources.size(), static_cast<unsigned long long>(o.settings.convergence.min_runs),
                static_cast<unsigned long long>(auto_run_limit(o.settings.convergence)), o.mode.c_str());
  } else {
    std::printf("Simulating %zu sources x %llu runs (%s mode) ...\n", sources.size(),
                static_cast<unsigned long long>(o.settings.runs_per_source), o.mode.c_str());
  }
  std::fflush(stdout);

  const auto simulate_start = std::chrono::steady_clock::now();
  const std::unique_ptr<TrajectoryModel> model = trajectory_model(o);
  TerminalProgress progress;
  const RockfallResult result = run_trajectories(ground, sources, *model, o, progress);
  const double simulate_seconds = seconds_since(simulate_start);

  const auto write_start = std::chrono::steady_clock::now();
  const nlohmann::json intensity_entry = write_layers_with_intensity(writer, hazard_layers(result.statistics.layers()), intensity);
  gis::add_trajectories(writer, result.lines, ground.spec().crs_wkt);

  record.add_input("dem", o.inputs.dem, &scene.dem.elevation.spec());
  if (!o.inputs.lithology.empty()) record.add_input("lithology", o.inputs.lithology, nullptr);
  if (!o.inputs.vegetation.empty()) record.add_input("vegetation", o.inputs.vegetation, nullptr);
  record.add_input("release", o.inputs.release, nullptr);
  if (!o.inputs.materials.empty()) record.add_input("materials", o.inputs.materials, nullptr);
  if (!o.scenario.empty()) record.add_input("scenario", o.scenario, nullptr);
  record.set_parameters(table.values());
  nlohmann::json stops = nlohmann::json::object();
  for (std::size_t r = 0; r < result.stop_counts.size(); ++r) {
    stops[to_string(static_cast<StopReason>(r))] = result.stop_counts[r];
  }
  record.set("seed", o.settings.seed);
  record.set("threads", result.threads);
  const auto sources_with_attributes =
      std::count_if(sources.begin(), sources.end(), [](const ReleaseSource& s) { return !s.conditions.empty(); });
  record.set("counts", {{"sources", sources.size()},
                        {"sources_with_attributes", sources_with_attributes},
                        {"trajectories", result.trajectories},
                        {"stop_reasons", stops},
                        {"fragments", result.fragments},
                        {"saved_trajectories", result.lines.size()}});
  record.set("runout", runout_summary(result.runouts));
  record.set("runs", runs_record(result, o.settings));
  record.set("convergence", convergence_record(result, o.settings));
  if (intensity) record.set("intensity", intensity_entry);
  const std::vector<std::string> trajectory_problems =
      o.mode == "fast" ? truncated_trajectory_problems(result.stop_counts, "[fast_bounce] max_time", o.fast.max_time)
                       : truncated_trajectory_problems(result.stop_counts, "[full] max_time", o.full.max_time);
  std::vector<std::string> problems = scene.problems;
  problems.insert(problems.end(), trajectory_problems.begin(), trajectory_problems.end());
  const std::vector<std::string> unconverged = convergence_problems(result, o.settings);
  problems.insert(problems.end(), unconverged.begin(), unconverged.end());
  record.set("notes", scene.notes);
  record.set("problems", problems);
  record.add_timing("read_inputs", read_seconds);
  record.add_timing("simulate", simulate_seconds);
  record.add_timing("write_layers", seconds_since(write_start));
  record.write(writer.temporary_path("run.json"));
  const std::string project_line =
      write_project_if_wanted(project, writer.staging_folder(), o.out, "rockfall", o.inputs.dem, o.inputs.release);
  writer.commit();

  std::printf("%llu trajectories in %.2f s (%.0f per second, %d threads); stopped: ",
              static_cast<unsigned long long>(result.trajectories), simulate_seconds,
              static_cast<double>(result.trajectories) / std::max(simulate_seconds, 1e-9), result.threads);
  for (std::size_t r = 0; r < result.stop_counts.size(); ++r) {
    std::printf("%s%s %llu", r ? ", " : "", to_string(static_cast<StopReason>(r)),
                static_cast<unsigned long long>(result.stop_counts[r]));
  }
  if (result.fragments > 0) std::printf("; fragments from fractures %llu", static_cast<unsigned long long>(result.fragments));
  std::printf("\n");
  for (const auto& line : convergence_lines(result, o.settings)) std::printf("%s\n", line.c_str());
  for (const auto& problem : trajectory_problems) std::printf("problem: %s\n", problem.c_str());
  for (const auto& problem : unconverged) std::printf("problem: %s\n", problem.c_str());
  if (intensity) std::printf("%s\n", intensity_summary(intensity_entry).c_str());
  std::printf("Layers written to %s (open the .tif files in QGIS: each has its style beside it)\n", o.out.c_str());
  if (!project_line.empty()) std::printf("%s\n", project_line.c_str());
  return 0;
}

}  // namespace

void add_rockfall_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line) {
  auto o = std::make_shared<RockfallOptions>();
  o->command_line = command_line;
  auto table = std::make_shared<ParameterTable>(parameter_table(*o));
  CLI::App* cmd = app.add_subcommand("rockfall", "Stochastic rock-fall trajectories and hazard layers");
  cmd->add_option("--dem", o->inputs.dem, "DEM raster (elevations in metres)")->required();
  cmd->add_option("--release", o->inputs.release, "Release raster or vector layer (points or polygons)")->required();
  cmd->add_option("--out", o->out, "Output folder for the layers")->required();
  cmd->add_option("--lithology", o->inputs.lithology, "Lithology class raster");
  cmd->add_option("--vegetation", o->inputs.vegetation, "Vegetation raster: class codes or deperdition coefficients (1/m)");
  cmd->add_option("--materials", o->inputs.materials, "Materials table (TOML); default: built-in");
  cmd->add_option("--scenario", o->scenario, "Scenario TOML: [run], [rock], [stochastic], [fast_bounce], [full] (see talus params)");
  auto* mode = cmd->add_option("--mode", o->mode, "Trajectory model: fast or full")->default_val("fast");
  auto* runs = cmd->add_option("--runs", o->runs_flag,
                               "Trajectories per release cell or point, or auto: until the envelope converges (default)");
  auto* shape = cmd->add_option("--block-shape", o->block_shape, "sphere, ellipsoid or box")->default_val("sphere");
  auto* size = cmd->add_option("--block-size", o->block_size, "Diameter D, or axes A,B,C (m)")->default_val("1");
  auto* density = cmd->add_option("--density", o->settings.rock.density, "Rock density (kg/m3)")->default_val(2700.0);
  auto* seed = cmd->add_option("--seed", o->settings.seed, "Random seed")->default_val(1)->check(whole_number());
  auto* threads = cmd->add_option("--threads", o->settings.threads, "Threads (default: all cores)");
  cmd->add_option("--crs", o->inputs.crs, "CRS of the inputs: EPSG:n, WKT, or local");
  auto* intensity = cmd->add_option("--intensity", o->intensity,
                                    "Intensity classes of intensity.tif: foen-2016 (default), FILE.toml or none");
  cmd->add_option("--only-source", o->settings.only_source,
                  "Simulate only this source (0-based, as source_id in trajectories.gpkg), to reproduce a trajectory")
      ->check(whole_number());
  cmd->add_option("--only-run", o->settings.only_run, "Simulate only this run of each source (0-based, as run_id)")
      ->check(whole_number());
  auto* project = cmd->add_option("--project", o->project,
                                  "on (default): also write project.qgz, hillshade.tif and quicklook/*.png with QGIS; off");
  cmd->callback([o, table, &action, mode, runs, shape, size, density, seed, threads, intensity, project] {
    const std::pair<CLI::Option*, const char*> flags[] = {{mode, "run.mode"},    {runs, "run.runs"},
                                                          {seed, "run.seed"},    {threads, "run.threads"},
                                                          {shape, "rock.shape"},
                                                          {size, "rock.size"},   {density, "rock.density"},
                                                          {intensity, "outputs.intensity"}, {project, "outputs.project"}};
    for (const auto& [option, key] : flags) {
      if (option->count() == 0) continue;
      const std::string name(key);
      table->pin(name.substr(0, name.find('.')), name.substr(name.find('.') + 1), option->get_name());
    }
    action = [o, table] { return run_rockfall_command(*o, *table); };
  });
}

void check_rockfall_scenario(const std::filesystem::path& scenario) {
  RockfallOptions o;
  o.scenario = scenario;
  ParameterTable table = parameter_table(o);
  resolve_parameters(o, table);
}

nlohmann::json rockfall_parameters() {
  RockfallOptions defaults;
  return parameter_table(defaults).describe();
}

}  // namespace talus::cli
