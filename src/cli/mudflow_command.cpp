// `talus mudflow` (docs/architecture.md section 3, issue 5): its options, parsed into the call that does
// the work (mudflow_job.hpp), with the lines on stdout and the progress on stderr.
#include <iterator>
#include <memory>

#include "commands.hpp"
#include "job_output.hpp"
#include "mudflow_job.hpp"
#include "mudflow_materials.hpp"
#include "mudflow_parameters.hpp"
#include "parameter_table.hpp"
#include "terminal_progress.hpp"
#include "whole_number.hpp"

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
                           {"outputs", "project", "--project"},     {"tiles", "memory", "--memory"},
                           {"tiles", "halo", "--halo"}};

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
  auto* memory = cmd->add_option("--memory", o->tiles.memory,
                                 "GB the run may use; a larger region runs the flow on a window (default: half of this machine's memory)");
  auto* halo = cmd->add_option("--halo", o->tiles.halo, "m the flow's window reaches beyond its release (default 5000)");
  cmd->callback([o, table, &action, duration, material, size, adaptive, rheology, snapshots, seed, threads, depth,
                 depth_field, start_time, intensity, project, memory, halo] {
    const CLI::Option* given[] = {duration, seed,      threads,     material,    size,       adaptive,  rheology,
                                  snapshots, depth,    depth_field, start_time, intensity, project,   memory, halo};
    static_assert(std::size(kFlags) == std::size(given));
    for (std::size_t k = 0; k < std::size(kFlags); ++k) {
      if (given[k]->count() > 0) table->pin(kFlags[k].section, kFlags[k].name, kFlags[k].option);
    }
    const bool adaptive_given = adaptive->count() > 0;
    action = [o, table, adaptive_given] {
      TerminalProgress progress;
      mudflow_job(*o, *table, adaptive_given, JobOutput{print_line, progress});
      return 0;
    };
  });
}

}  // namespace talus::cli
