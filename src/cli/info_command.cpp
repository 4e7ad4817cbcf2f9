// `talus info`: the aligned scene in a few lines (issue: foundation, item 8): size,
// resolution, CRS, extent, lithology classes and their share, vegetation range, release
// count and area, and every problem found.
#include <algorithm>
#include <cstdio>
#include <iostream>
#include <limits>
#include <map>

#include "commands.hpp"
#include "release_convention.hpp"
#include "talus/gis/scene.hpp"

namespace talus::cli {
namespace {

struct InfoOptions {
  gis::SceneInputs inputs;
};

void print_dem(const gis::Scene& scene) {
  const Grid<double>& dem = scene.dem.elevation;
  const GridSpec& spec = dem.spec();
  std::size_t valid = 0;
  double low = std::numeric_limits<double>::infinity(), high = -low;
  for (std::size_t i = 0; i < dem.size(); ++i) {
    if (!dem.is_valid(i)) continue;
    ++valid;
    low = std::min(low, dem[i]);
    high = std::max(high, dem[i]);
  }
  const auto& gt = spec.geotransform;
  std::printf("DEM          %s\n", scene.inputs.dem.c_str());
  std::printf("  size       %d x %d cells of %.6g x %.6g m (%.6g x %.6g m)\n", spec.width, spec.height,
              spec.cell_width(), spec.cell_height(), spec.width * spec.cell_width(), spec.height * spec.cell_height());
  std::printf("  CRS        %s\n", scene.dem.crs_name.c_str());
  std::printf("  extent     x %.3f .. %.3f m, y %.3f .. %.3f m\n", gt[0], gt[0] + spec.width * gt[1],
              gt[3] + spec.height * gt[5], gt[3]);
  std::printf("  elevation  %.1f .. %.1f m over %zu valid cells (%.1f %%)\n", low, high, valid,
              100.0 * static_cast<double>(valid) / static_cast<double>(dem.size()));
}

void print_lithology(const gis::Scene& scene) {
  const Grid<double>& dem = scene.dem.elevation;
  std::map<int, std::size_t> counts;
  std::size_t valid = 0;
  for (std::size_t i = 0; i < dem.size(); ++i) {
    if (!dem.is_valid(i)) continue;
    ++valid;
    ++counts[scene.lithology[i]];
  }
  std::printf("Lithology    %s\n", scene.inputs.lithology.empty() ? "(none: default class)" : scene.inputs.lithology.c_str());
  for (const auto& [code, count] : counts) {
    std::printf("  %3d %-44s %6.2f %%\n", code, scene.materials.find_lithology(code)->name.c_str(),
                100.0 * static_cast<double>(count) / static_cast<double>(valid));
  }
}

void print_vegetation(const gis::Scene& scene) {
  const Grid<double>& dem = scene.dem.elevation;
  std::printf("Vegetation   %s\n", scene.inputs.vegetation.empty() ? "(none: default class)" : scene.inputs.vegetation.c_str());
  if (scene.vegetation_classes) {
    std::map<int, std::size_t> counts;
    std::size_t valid = 0;
    for (std::size_t i = 0; i < dem.size(); ++i) {
      if (!dem.is_valid(i)) continue;
      ++valid;
      ++counts[(*scene.vegetation_classes)[i]];
    }
    for (const auto& [code, count] : counts) {
      const VegetationClass* c = scene.materials.find_vegetation(code);
      std::printf("  %3d %-24s c = %-8.4g 1/m %6.2f %%\n", code, c->name.c_str(), c->deperdition,
                  100.0 * static_cast<double>(count) / static_cast<double>(valid));
    }
  }
  double low = std::numeric_limits<double>::infinity(), high = -low, sum = 0;
  std::size_t valid = 0;
  for (std::size_t i = 0; i < dem.size(); ++i) {
    if (!dem.is_valid(i)) continue;
    ++valid;
    low = std::min(low, scene.vegetation[i]);
    high = std::max(high, scene.vegetation[i]);
    sum += scene.vegetation[i];
  }
  std::printf("  deperdition coefficient %.4g .. %.4g 1/m, mean %.4g 1/m\n", low, high, sum / static_cast<double>(valid));
}

void print_release(const gis::Scene& scene) {
  if (!scene.release) {
    std::printf("Release      (none given)\n");
    return;
  }
  const ReleaseSet& release = *scene.release;
  std::printf("Release      %s\n", scene.inputs.release.c_str());
  if (!release.points.empty()) std::printf("  points     %zu\n", release.points.size());
  if (release.cell_count() > 0) {
    float low = std::numeric_limits<float>::infinity(), high = 0;
    for (std::size_t i = 0; i < release.depth.size(); ++i) {
      if (release.depth[i] <= 0.0f) continue;
      low = std::min(low, release.depth[i]);
      high = std::max(high, release.depth[i]);
    }
    std::printf("  cells      %zu, area %.0f m2, depth %.3g .. %.3g m\n", release.cell_count(), release.area(),
                static_cast<double>(low), static_cast<double>(high));
  }
  // As `talus mudflow` reads the depths by default ([mud] release_thickness = auto).
  const ReleaseConvention convention =
      release_convention(scene.ground_model(), release, ReleaseThicknessChoice::automatic);
  if (convention.volume > 0.0) std::printf("  mud flow   %s\n", release_convention_text(convention).c_str());
}

int run_info(const InfoOptions& options) {
  const gis::Scene scene = gis::load_scene(options.inputs);
  print_dem(scene);
  print_lithology(scene);
  print_vegetation(scene);
  print_release(scene);
  std::printf("Notes\n");
  for (const auto& note : scene.notes) std::printf("  - %s\n", note.c_str());
  if (scene.problems.empty()) {
    std::printf("Problems     none\n");
  } else {
    std::printf("Problems     %zu\n", scene.problems.size());
    for (const auto& problem : scene.problems) std::printf("  - %s\n", problem.c_str());
  }
  return 0;
}

}  // namespace

void add_info_command(CLI::App& app, Action& action) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* info = app.add_subcommand("info", "Print the aligned scene: grid, CRS, classes, release, problems");
  info->add_option("dem", options->inputs.dem, "DEM raster (elevations in metres)")->required();
  info->add_option("--lithology", options->inputs.lithology, "Lithology class raster (codes of the materials table)");
  info->add_option("--vegetation", options->inputs.vegetation,
                   "Vegetation raster: class codes, or deperdition coefficients in 1/m");
  info->add_option("--release", options->inputs.release, "Release raster or vector layer (points or polygons)");
  info->add_option("--materials", options->inputs.materials, "Materials table (TOML); default: built-in");
  info->add_option("--crs", options->inputs.crs, "CRS of the inputs: EPSG:n, WKT, or local");
  info->callback([options, &action] { action = [options] { return run_info(*options); }; });
}

}  // namespace talus::cli
