// `talus rockfall` (docs/architecture.md section 3, issue 3): its options, parsed into the call that does
// the work (rockfall_job.hpp), with the lines on stdout and the progress on stderr.
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "job_output.hpp"
#include "parameter_table.hpp"
#include "rockfall_job.hpp"
#include "rockfall_parameters.hpp"
#include "terminal_progress.hpp"
#include "whole_number.hpp"

namespace talus::cli {

void add_rockfall_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line,
                          const ProcessRanks& ranks) {
  auto o = std::make_shared<RockfallOptions>();
  o->command_line = command_line;
  auto table = std::make_shared<ParameterTable>(rockfall_parameter_table(*o));
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
  auto* memory = cmd->add_option("--memory", o->tiles.memory,
                                 "GB the run may use; a larger region runs in tiles (default: half of this machine's memory)");
  auto* halo = cmd->add_option("--halo", o->tiles.halo, "m a tile's rocks may run beyond it (default 2000)");
  auto* tile_size = cmd->add_option("--tile-size", o->tiles.size, "Cells on a side of a tile (default: from --memory)");
  auto* project = cmd->add_option("--project", o->project,
                                  "on (default): also write project.qgz, hillshade.tif and quicklook/*.png with QGIS; off");
  cmd->callback([o, table, &action, &ranks, mode, runs, shape, size, density, seed, threads, intensity, project, memory,
                 halo, tile_size] {
    const std::pair<CLI::Option*, const char*> flags[] = {{mode, "run.mode"},    {runs, "run.runs"},
                                                          {seed, "run.seed"},    {threads, "run.threads"},
                                                          {shape, "rock.shape"},
                                                          {size, "rock.size"},   {density, "rock.density"},
                                                          {intensity, "outputs.intensity"}, {project, "outputs.project"},
                                                          {memory, "tiles.memory"},  {halo, "tiles.halo"},
                                                          {tile_size, "tiles.size"}};
    for (const auto& [option, key] : flags) {
      if (option->count() == 0) continue;
      const std::string name(key);
      table->pin(name.substr(0, name.find('.')), name.substr(name.find('.') + 1), option->get_name());
    }
    action = [o, table, &ranks] {
      TerminalProgress progress(ranks.root());
      rockfall_job(*o, *table, JobOutput{rank_say(ranks.root()), progress}, ranks);
      return 0;
    };
  });
}

}  // namespace talus::cli
