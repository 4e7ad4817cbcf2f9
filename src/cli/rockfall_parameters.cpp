// The parameters of `talus rockfall` (rockfall_parameters.hpp).
#include "rockfall_parameters.hpp"

#include <cstdint>
#include <string>
#include <vector>

#include "number_list.hpp"
#include "rockfall_layers.hpp"
#include "run_project.hpp"
#include "talus/core/errors.hpp"
#include "talus/rockfall/envelope_convergence.hpp"
#include "talus/rockfall/rockfall_statistics.hpp"

namespace talus::cli {
namespace {

// --block-shape, [rock] shape.
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

// --runs (or [run] runs) into the settings, and the convergence parameters checked: a tolerance
// in (0, 1); with auto, min_runs >= 2 and max_runs >= min_runs; --only-run below the runs.
void validate_runs(RockfallOptions& o, const ParameterTable& table) {
  if (!o.runs_flag.empty()) o.runs = parse_count_or_auto("--runs", o.runs_flag);
  RockfallSettings& s = o.settings;
  s.auto_runs = o.runs.automatic;
  if (!s.auto_runs) s.runs_per_source = o.runs.count;
  if (!s.auto_runs && s.runs_per_source == 0) throw InputError(table.where("run", "runs") + " 0: at least one run per source");
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

}  // namespace

ParameterTable rockfall_parameter_table(RockfallOptions& o) {
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
  table.add("run", "redraws", "",
            "a trajectory that failed numerically, after the full model's restarts, is drawn again from a fresh random "
            "stream up to this many times before it is recorded as failed (docs/rockfall-full.md, section 5)",
            &o.settings.redraws, Range{0, 100, false, false});
  table.add("run", "failure_share", "%",
            "a run whose failed trajectories exceed this share of its trajectories fails (exit code 3, nothing "
            "written); below it they are recorded in run.json and reported, and the layers miss them",
            &o.failure_share, Range{0, 100, false, false});
  table.add("run", "saved_trajectories", "", "at most this many lines in trajectories.gpkg", &o.settings.saved_trajectories, Range{0, 1e+07, false, false});
  table.add("tiles", "memory", "GB",
            "memory the run may use; a region whose ground model needs more runs in tiles (docs/study.md, Tiles)",
            &o.tiles.memory, Range{0.1, 1e6, false, false, 0, "half of this machine's memory"});
  table.add("tiles", "halo", "m", "how far beyond its tile a rock may run; one that reaches the halo's edge stops there "
            "and is reported (stop reason tile_edge)", &o.tiles.halo, Range{0, 1e6, false, false});
  table.add("tiles", "size", "cells", "cells on a side of a tile (without its halo)", &o.tiles.size,
            Range{16, 1e6, false, false, 0, "the largest that [tiles] memory allows"});
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
  table.add("full", "max_retries", "", "step halvings before the step counts as failed (then restarts)", &m.max_retries, Range{0, 60, false, false});
  table.add("full", "restarts", "",
            "a step that fails after max_retries halvings restarts the rock from its last sound state with contact steps "
            "a quarter as long, up to this many times per rock (docs/rockfall-full.md, section 5)",
            &m.restarts, Range{0, 20, false, false});
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

RunChoices resolve_rockfall_parameters(RockfallOptions& o, ParameterTable& table) {
  // The scenario file sets every parameter it names, except those given as flags (pinned).
  if (!o.scenario.empty()) table.apply_scenario(o.scenario, {});
  if (o.mode != "fast" && o.mode != "full") throw InputError("--mode " + o.mode + ": use fast or full");
  o.settings.rock.shape = parse_shape(o.block_shape);
  o.settings.rock.axes = parse_size(o.block_size);
  if (o.settings.rock.shape == BlockShape::sphere && o.settings.rock.axes.maxCoeff() != o.settings.rock.axes.minCoeff()) {
    throw InputError("--block-size " + o.block_size + ": a sphere has one diameter; use --block-shape ellipsoid or box");
  }
  validate_runs(o, table);
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
  o.full.fracture_strength = 1000.0 * o.fracture_strength;
  RunChoices choices;
  choices.intensity = chosen_intensity(o.intensity, "rockfall", rockfall_hazard_layers(RockfallLayers{}));
  choices.project = project_wanted(o.project);
  return choices;
}

void check_rockfall_scenario(const std::filesystem::path& scenario) {
  RockfallOptions o;
  o.scenario = scenario;
  ParameterTable table = rockfall_parameter_table(o);
  resolve_rockfall_parameters(o, table);
}

nlohmann::json rockfall_parameters() {
  RockfallOptions defaults;
  return rockfall_parameter_table(defaults).describe();
}

}  // namespace talus::cli
