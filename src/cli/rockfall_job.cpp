// The work of `talus rockfall` as one library call (docs/architecture.md section 3, issue 3; issue 19):
// stochastic rock-fall trajectories on the scene and every rock-fall layer, trajectories.gpkg and
// run.json, committed as one set.
#include "rockfall_job.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

#include "envelope_convergence_report.hpp"
#include "failed_trajectories.hpp"
#include "intensity_layer.hpp"
#include "rockfall_layers.hpp"
#include "rockfall_tiles.hpp"
#include "run_project.hpp"
#include "tile_plan.hpp"
#include "truncated_trajectories.hpp"
#include "unit_parts.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/layer_writer.hpp"
#include "talus/gis/run_record.hpp"
#include "talus/gis/scene.hpp"
#include "talus/gis/trajectory_writer.hpp"
#include "talus/rockfall/fast_bounce.hpp"
#include "talus/rockfall/full_model.hpp"
#include "talus/rockfall/monte_carlo.hpp"
#include "talus/rockfall/release_rock.hpp"
#include "talus/rockfall/rockfall_shares.hpp"

namespace talus::cli {
namespace {

// The run in one line, for the TALUS_SCENARIO metadata of every layer.
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

// How far around a rock at a halo's edge the trajectory models may look (m): two sample spacings
// (the path between the samples that are checked against the halo), 10 m for the longest step,
// and four times the largest rock's axis (its piston carpet, a fragment's start).
double tile_margin(const RockfallOptions& o, const std::vector<ReleaseSource>& sources) {
  double largest = o.settings.rock.axes.maxCoeff();
  for (const ReleaseSource& s : sources) largest = std::max(largest, release_rock(o.settings.rock, s.conditions).axes.maxCoeff());
  largest *= 1.0 + o.settings.stochastic.size_variation;
  const double spacing = o.mode == "fast" ? o.fast.sample_spacing : o.full.sample_spacing;
  return 2.0 * spacing + 10.0 + 4.0 * largest;
}

// The scene read and checked, before any trajectory: the region whole with its ground model, or,
// when it runs in tiles, the region's DEM and release alone (the tiles read the rest).
struct RockfallScene {
  RunChoices choices;
  gis::Scene scene;
  TilePlan plan;
  std::optional<GroundModel> ground;
  std::vector<ReleaseSource> sources;
};

RockfallScene read_rockfall_scene(RockfallOptions& o, RunChoices choices) {
  o.inputs.run_rock = o.settings.rock;
  gis::Scene scene = gis::load_region(o.inputs);
  std::vector<ReleaseSource> sources = release_sources(*scene.release);
  const std::optional<std::uint64_t>& only_source = o.settings.only_source;
  if (only_source && *only_source >= sources.size()) {
    throw InputError("--only-source " + std::to_string(*only_source) + ": sources are numbered 0 to " +
                     std::to_string(sources.size() - 1) + " (" + o.inputs.release.string() + ")");
  }
  TilePlan plan = plan_tiles(scene.dem.elevation.spec(), o.tiles, tile_margin(o, sources));
  std::optional<GroundModel> ground;
  if (!plan.tiled()) {
    gis::add_ground_maps(scene);
    ground.emplace(scene.ground_model());
  }
  return {std::move(choices), std::move(scene), std::move(plan), std::move(ground), std::move(sources)};
}

// What the units of work committed to o.unit_parts depend on: the scenario's record and how the
// run is cut into units.
std::string unit_parts_key(const RockfallOptions& o, const TilePlan& plan) {
  nlohmann::ordered_json key = nlohmann::ordered_json::parse(o.unit_key);
  key["units"] = {{"tiles", plan.tiles.size()},
                  {"tile_cells", plan.core_cells},
                  {"halo_cells", plan.halo_cells},
                  {"sources_per_unit", kSourcesPerUnit}};
  return key.dump(1);
}

// This rank's share of the trajectories; on rank 0, every rank's shares joined (rockfall_shares.hpp).
std::optional<RockfallResult> simulate_shares(const RockfallScene& r, const TrajectoryModel& model, RockfallOptions& o,
                                              const JobOutput& output, const ProcessRanks& ranks, TileLines& tile_lines) {
  o.settings.share = {static_cast<std::uint32_t>(ranks.rank()), static_cast<std::uint32_t>(ranks.size()), nullptr};
  const TrajectoryRunner run = [&](const GroundModel& ground, const RockfallSettings& settings, Progress& part) {
    return run_rockfall(ground, r.sources, model, settings, &part);
  };
  if (r.plan.tiled() || !o.unit_parts.empty()) {
    std::optional<UnitParts> parts;
    if (!o.unit_parts.empty()) {
      parts.emplace(o.unit_parts, ranks.rank(), ranks.size());
      together(ranks, [&] {
        if (ranks.root()) parts->prepare(unit_parts_key(o, r.plan));
      });
    }
    std::size_t resumed = 0;
    std::optional<RockfallResult> joined = simulate_units(r.scene, r.ground ? &*r.ground : nullptr, r.plan, r.sources,
                                                          o.settings, run, output.progress, ranks,
                                                          parts ? &*parts : nullptr, tile_lines, resumed);
    if (resumed > 0) output.say(printf_text("resumed: %zu units of work were committed by an earlier run", resumed));
    return joined;
  }
  std::optional<RockfallResult> share;
  together(ranks, [&] { share = run(*r.ground, o.settings, output.progress); });
  if (ranks.size() == 1) return share;
  const std::vector<std::vector<std::uint8_t>> messages = ranks.gather(encode_share(*share));
  if (!ranks.root()) return std::nullopt;
  std::vector<RockfallResult> shares;
  for (const auto& bytes : messages) shares.push_back(decode_share(bytes, r.scene.dem.elevation));
  return join_shares(std::move(shares), o.settings);
}

// The tiles in run.json (issue 19, item 4): none when the run was not tiled.
nlohmann::json tiles_record(const TilePlan& plan, const TileChoice& choice) {
  if (!plan.tiled()) return nullptr;
  return {{"tiles", plan.tiles.size()},
          {"tile_cells", plan.core_cells},
          {"halo_m", choice.halo},
          {"halo_cells", plan.halo_cells},
          {"margin_cells", plan.margin_cells},
          {"memory_gb", plan.memory_bytes / 1e9},
          {"estimated_tile_gb", plan.tile_bytes / 1e9},
          {"estimated_region_gb", plan.region_bytes / 1e9}};
}

}  // namespace

void rockfall_job(RockfallOptions& o, ParameterTable& table, const JobOutput& output, const ProcessRanks& ranks) {
  const auto start = std::chrono::steady_clock::now();
  std::optional<gis::LayerWriter> staged;
  std::optional<RockfallScene> read;
  together(ranks, [&] {
    RunChoices choices = resolve_rockfall_parameters(o, table);
    // The output folder is checked and staged before any work (issue 18, item 3), by rank 0.
    if (ranks.root()) {
      staged.emplace(o.out, std::map<std::string, std::string>{{"TALUS_PROCESS", "rock fall"},
                                                               {"TALUS_SCENARIO", scenario_text(o)}});
    }
    read = read_rockfall_scene(o, std::move(choices));
  });
  const auto& [intensity, project] = read->choices;
  const gis::Scene& scene = read->scene;
  const std::vector<ReleaseSource>& sources = read->sources;
  gis::RunRecord record;
  record.set_command_line(o.command_line);
  const double read_seconds = seconds_since(start);
  for (const auto& note : scene.notes) output.say("note: " + note);
  for (const auto& problem : scene.problems) output.say("problem: " + problem);
  if (o.settings.auto_runs) {
    output.say(printf_text("Simulating %zu sources x %llu to %llu runs until converged (--runs auto, %s mode) ...",
                           sources.size(), static_cast<unsigned long long>(o.settings.convergence.min_runs),
                           static_cast<unsigned long long>(auto_run_limit(o.settings.convergence)), o.mode.c_str()));
  } else {
    output.say(printf_text("Simulating %zu sources x %llu runs (%s mode) ...", sources.size(),
                           static_cast<unsigned long long>(o.settings.runs_per_source), o.mode.c_str()));
  }

  const auto simulate_start = std::chrono::steady_clock::now();
  if (read->plan.tiled()) {
    const TilePlan& plan = read->plan;
    output.say(printf_text("Tiles: %zu of at most %d x %d cells with a halo of %g m, for --memory %.3g GB "
                           "(estimated %.3g GB a tile, %.3g GB for the region)",
                           plan.tiles.size(), plan.core_cells, plan.core_cells, o.tiles.halo, plan.memory_bytes / 1e9,
                           plan.tile_bytes / 1e9, plan.region_bytes / 1e9));
  }
  const std::unique_ptr<TrajectoryModel> model = trajectory_model(o);
  TileLines tile_lines;
  const std::optional<RockfallResult> joined = simulate_shares(*read, *model, o, output, ranks, tile_lines);
  if (!ranks.root()) return;  // rank 0 writes
  const RockfallResult& result = *joined;
  const double simulate_seconds = seconds_since(simulate_start);
  check_failure_share(result, o.failure_share, o.command_line);
  gis::LayerWriter& writer = *staged;
  // The maps say how many trajectories they miss (docs/layers.md, "Metadata").
  writer.set_metadata("TALUS_TRAJECTORIES", std::to_string(result.trajectories + result.failures.size()));
  writer.set_metadata("TALUS_MISSING_TRAJECTORIES", std::to_string(result.failures.size()));

  const auto write_start = std::chrono::steady_clock::now();
  const nlohmann::json intensity_entry = write_layers_with_intensity(writer, rockfall_hazard_layers(result.statistics.layers()), intensity);
  gis::add_trajectories(writer, result.lines, scene.dem.elevation.spec().crs_wkt);

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
  record.set("mpi_ranks", ranks.size());
  const auto sources_with_attributes =
      std::count_if(sources.begin(), sources.end(), [](const ReleaseSource& s) { return !s.conditions.empty(); });
  record.set("counts", {{"sources", sources.size()},
                        {"sources_with_attributes", sources_with_attributes},
                        {"trajectories", result.trajectories},
                        {"stop_reasons", stops},
                        {"fragments", result.fragments},
                        {"failed_trajectories", result.failures.size()},
                        {"saved_trajectories", result.lines.size()}});
  record.set("runout", runout_summary(result.runouts));
  record.set("runs", runs_record(result, o.settings));
  record.set("convergence", convergence_record(result, o.settings));
  if (intensity) record.set("intensity", intensity_entry);
  record.set("tiles", tiles_record(read->plan, o.tiles));
  record.set("recovery", recovery_record(result, o.failure_share));
  const std::vector<std::string> trajectory_problems =
      o.mode == "fast" ? truncated_trajectory_problems(result.stop_counts, "[fast_bounce] max_time", o.fast.max_time, o.tiles.halo)
                       : truncated_trajectory_problems(result.stop_counts, "[full] max_time", o.full.max_time, o.tiles.halo);
  std::vector<std::string> notes = scene.notes;
  notes.insert(notes.end(), tile_lines.notes.begin(), tile_lines.notes.end());
  std::vector<std::string> problems = scene.problems;
  problems.insert(problems.end(), tile_lines.problems.begin(), tile_lines.problems.end());
  problems.insert(problems.end(), trajectory_problems.begin(), trajectory_problems.end());
  const std::vector<std::string> failed = failure_problems(result, o.failure_share);
  problems.insert(problems.end(), failed.begin(), failed.end());
  const std::vector<std::string> unconverged = convergence_problems(result, o.settings);
  problems.insert(problems.end(), unconverged.begin(), unconverged.end());
  const std::vector<std::string> thin_classes = intensity ? intensity_problems(intensity_entry) : std::vector<std::string>{};
  problems.insert(problems.end(), thin_classes.begin(), thin_classes.end());
  record.set("notes", notes);
  record.set("problems", problems);
  record.add_timing("read_inputs", read_seconds);
  record.add_timing("simulate", simulate_seconds);
  record.add_timing("write_layers", seconds_since(write_start));
  record.write(writer.temporary_path("run.json"));
  const std::string project_line =
      write_project_if_wanted(project, writer.staging_folder(), o.out, "rockfall", o.inputs.dem, o.inputs.release);
  writer.commit();

  const std::string workers = ranks.size() == 1 ? printf_text("%d threads", result.threads)
                                                : printf_text("%d MPI ranks x %d threads", ranks.size(), result.threads);
  std::string summary = printf_text("%llu trajectories in %.2f s (%.0f per second, %s); stopped: ",
                                     static_cast<unsigned long long>(result.trajectories), simulate_seconds,
                                     static_cast<double>(result.trajectories) / std::max(simulate_seconds, 1e-9), workers.c_str());
  for (std::size_t r = 0; r < result.stop_counts.size(); ++r) {
    const auto reason = static_cast<StopReason>(r);
    if (reason == StopReason::tile_edge && result.stop_counts[r] == 0) continue;  // shown when it happened
    summary += printf_text("%s%s %llu", r ? ", " : "", to_string(reason), static_cast<unsigned long long>(result.stop_counts[r]));
  }
  if (result.fragments > 0) summary += printf_text("; fragments from fractures %llu", static_cast<unsigned long long>(result.fragments));
  output.say(summary);
  for (const auto& note : tile_lines.notes) output.say("note: " + note);
  for (const auto& problem : tile_lines.problems) output.say("problem: " + problem);
  for (const auto& line : convergence_lines(result, o.settings)) output.say(line);
  for (const auto& problem : trajectory_problems) output.say("problem: " + problem);
  for (const auto& problem : failed) output.say("problem: " + problem);
  for (const auto& problem : unconverged) output.say("problem: " + problem);
  if (intensity) output.say(intensity_summary(intensity_entry));
  for (const auto& problem : thin_classes) output.say("problem: " + problem);
  output.say("Layers written to " + o.out.string() + " (open the .tif files in QGIS: each has its style beside it)");
  if (!project_line.empty()) output.say(project_line);
}


}  // namespace talus::cli
