// The parameters of `talus mudflow` (mudflow_parameters.hpp).
#include "mudflow_parameters.hpp"

#include <cstdint>
#include <optional>
#include <sstream>
#include <string>

#include "mudflow_layers.hpp"
#include "run_project.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/release_reader.hpp"
#include "talus/mudflow/release_particles.hpp"
#include "talus/mudflow/rheology.hpp"

namespace talus::cli {
namespace {

// Particle snapshots: the most a run writes.
constexpr double kMaxSnapshots = 100000.0;

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
  table.require(o.release_thickness == "auto" || o.release_thickness == "normal" || o.release_thickness == "vertical",
                "mud", "release_thickness", o.release_thickness, "use auto, normal or vertical");
  o.release_thickness_choice = parse_release_thickness(o.release_thickness);
  table.require(o.pressure == "normal" || o.pressure == "vertical", "mud", "pressure", o.pressure,
                "use normal or vertical");
  o.settings.pressure = parse_pressure_column(o.pressure);
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

}  // namespace

// Every MudflowSettings field (mudflow_simulation.hpp, rheology.hpp) as a scenario parameter.
ParameterTable mudflow_parameter_table(MudflowOptions& o) {
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
            "how a release depth is measured: normal (to the ground, the thin-layer convention), vertical, or auto "
            "(vertical for a raster of negative depths, a DEM of difference; normal otherwise)",
            &o.release_thickness);
  table.add("mud", "pressure", "",
            "whose weight the pressure in the mud is: normal (the thin-layer column normal to the ground, the "
            "default) or vertical (the vertical column, as com1DFA's default SPH option; for code-to-code comparison)",
            &o.pressure);
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
  table.add("adaptivity", "crowded_merge", "-",
            "crowded fusion: groups in mud deeper than their particles resolve merge while the merged particle sums "
            "over at most this many finest support radii; adaptive runs only (docs/mudflow.md section 8)",
            &s.crowded_merge, Range{1, 4, false, false, 0, "off"});
  table.add("time_steps", "courant", "-",
            "C in dt = C min(s / (c + w), sqrt(s / |a|)), w the fastest closing speed of a neighbour", &s.courant, Range{0, 1, true, false});
  table.add("time_steps", "cells_per_step", "-",
            "a particle's step crosses at most this many DEM cells; 0: 1 in adaptive runs with crowded fusion, 0.5 "
            "otherwise (docs/mudflow.md section 7)",
            &s.cells_per_step, Range{0, 10, true, false, 0, "automatic"});
  table.add("time_steps", "longest_step", "s", "step of level 0; level k steps are longest_step / 2^k", &s.longest_step, Range{0.001, 10, false, false});
  table.add("time_steps", "deepest_level", "", "deepest step level", &s.deepest_level, Range{0, 30, false, false});
  table.add("time_steps", "guard", "", "detect blown-up steps and retry them with halved steps", &s.guard);
  table.add("time_steps", "max_retries", "", "step halvings before a run fails with exit code 3", &s.max_retries, Range{0, 20, false, false});
  table.add("time_steps", "unguarded_step", "s", "> 0: one global step that ignores the Courant condition (tests of the guard)",
            &s.unguarded_step, Range{1e-4, 10, false, false, 0, "off"});
  table.add("contact", "curvature", "",
            "the basal normal stress includes the centripetal term rho0 h u^2 kappa of the ground's curvature", &s.curvature);
  table.add("contact", "node_normals", "",
            "the ground normal is interpolated bilinearly between normals at the nodes (each the mean slope of the "
            "node's four squares), as in com1DFA, instead of each square's own",
            &s.node_normals);
  table.add("contact", "step_normal", "",
            "gravity's pull along the ground is taken on the normal averaged between the foot's and the ground's one "
            "step ahead along the velocity, as in com1DFA, instead of the foot's alone",
            &s.step_normal);
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
  table.add("rheology", "yield_stress", "Pa", "yield stress tau_y of Voellmy and Bingham (0: Voellmy's own law)", &r.yield_stress, Range{0, 1e7, false, false});
  table.add("rheology", "internal_viscosity", "m2/s", "kinematic viscosity of the internal friction between particles",
            &r.internal_viscosity, Range{0, 1e4, false, false});
  table.add("rheology", "lateral_mixing", "-",
            "C of the drag (C / s) |u - u_mean| (u - u_mean) of each column towards the mean velocity of its "
            "neighbours, s its footprint's side (com1DFA's artificial viscosity: 100); 0 none",
            &r.lateral_mixing, Range{0, 1e4, false, false});
  table.add("deposition", "stop_speed", "m/s", "mud slower than this for stop_duration, and held by the bed, deposits",
            &s.stop_speed, Range{0, 100, false, false});
  table.add("deposition", "stop_duration", "s", "how long the mud must stay slower than stop_speed", &s.stop_duration, Range{0, 86400, false, false});
  table.add("entrainment", "rate", "1/m", "entrainment rate E: the bed erodes at E h |u| (m/s) where erodible material lies",
            &s.entrainment_rate, Range{0, 10, false, false});
  table.add("outputs", "arrival_depth", "m", "a cell is reached when its flow depth first exceeds this", &s.arrival_depth, Range{0, 100, true, false});
  table.add("outputs", "map_interval", "s", "flow depth, velocity and pressure maxima are sampled this often",
            &s.map_interval, Range{0.01, 3600, false, false});
  table.add("outputs", "snapshot_interval", "s", "> 0: particles.gpkg holds the particles this often", &s.snapshot_interval, Range{0.01, 86400, false, false, 0, "none"});
  table.add("tiles", "memory", "GB",
            "memory the run may use; a region whose ground model needs more runs the flow on a window around its "
            "release (docs/study.md, Tiles)",
            &o.tiles.memory, Range{0.1, 1e6, false, false, 0, "half of this machine's memory"});
  table.add("tiles", "halo", "m", "how far beyond its release the flow's window reaches; mud that crosses its edge "
            "leaves the flow there and is reported", &o.tiles.halo, Range{0, 1e6, false, false});
  table.add("tiles", "size", "cells", "any size runs the flow on its window whatever the memory (for tests)",
            &o.tiles.size, Range{16, 1e6, false, false, 0, "only when [tiles] memory asks for it"});
  table.add("outputs", "project", "",
            "on: also write project.qgz, hillshade.tif and quicklook/*.png with QGIS (python3-qgis); off: not", &o.project);
  table.add("outputs", "intensity", "",
            "intensity classes of intensity.tif: a built-in guideline (foen-2016), a guideline file FILE.toml, or none",
            &o.intensity);
  table.add("outputs", "snapshot_start", "",
            "date-time of the release on particles.gpkg's clock, YYYY-MM-DDTHH:MM:SS (no time zone)", &o.snapshot_start);
  return table;
}

RunChoices resolve_mudflow_parameters(MudflowOptions& o, ParameterTable& table, bool adaptive_given) {
  // The scenario file sets every parameter it names, except those given as flags; the material
  // preset then sets those that neither gives.
  if (!o.scenario.empty()) table.apply_scenario(o.scenario, {});
  apply_material(o, table);
  if (adaptive_given) o.settings.adaptive = parse_on_off(o.adaptive);
  validate(o, table);
  RunChoices choices;
  choices.intensity = chosen_intensity(o.intensity, "mudflow", mudflow_hazard_layers(FlowLayers{}));
  choices.project = project_wanted(o.project);
  return choices;
}

void check_mudflow_scenario(const std::filesystem::path& scenario) {
  MudflowOptions o;
  o.scenario = scenario;
  ParameterTable table = mudflow_parameter_table(o);
  resolve_mudflow_parameters(o, table, false);
}

nlohmann::json mudflow_parameters() {
  MudflowOptions defaults;
  ParameterTable table = mudflow_parameter_table(defaults);
  apply_material(defaults, table);
  return table.describe();
}

nlohmann::json mudflow_materials() { return MudflowMaterials::built_in().describe(); }

}  // namespace talus::cli
