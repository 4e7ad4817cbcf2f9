// Cutting a region into tiles with a halo and a margin (tile_plan.hpp; issue 19, item 4).
#include "tile_plan.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "talus/core/errors.hpp"

namespace talus::cli {
namespace {

// Half of the machine's physical memory (bytes): the default budget.
double default_memory() {
  const double pages = static_cast<double>(::sysconf(_SC_PHYS_PAGES));
  const double page = static_cast<double>(::sysconf(_SC_PAGE_SIZE));
  return pages > 0 && page > 0 ? 0.5 * pages * page : 8e9;
}

std::string gigabytes(double bytes) {
  std::ostringstream text;
  text.precision(3);
  text << bytes / 1e9 << " GB";
  return text.str();
}

}  // namespace

TilePlan plan_tiles(const GridSpec& region, const TileChoice& choice, double margin_m) {
  TilePlan plan;
  plan.memory_bytes = choice.memory > 0 ? choice.memory * 1e9 : default_memory();
  const double cell = std::min(region.cell_width(), region.cell_height());
  plan.halo_cells = static_cast<int>(std::ceil(choice.halo / cell));
  plan.margin_cells = static_cast<int>(std::ceil(margin_m / cell)) + 2;
  plan.region_bytes = static_cast<double>(region.cell_count()) * kRegionBytesPerCell;
  const double for_tiles = plan.memory_bytes - kBaseBytes - plan.region_bytes;
  const auto whole_region = [&] {
    plan.tiles = {Tile{region, region, TileBounds{}}};
    plan.core_cells = std::max(region.width, region.height);
    plan.tile_bytes = static_cast<double>(region.cell_count()) * kTileBytesPerCell;
  };
  if (choice.size == 0 && static_cast<double>(region.cell_count()) * kTileBytesPerCell <= for_tiles) {
    whole_region();
    return plan;
  }
  if (for_tiles <= 0) {
    std::ostringstream message;
    message << "--memory " << gigabytes(plan.memory_bytes) << ": the region's " << region.width << " x " << region.height
            << " cells need about " << gigabytes(kBaseBytes + plan.region_bytes) << " before any tile (its DEM, release, "
            << "statistics and layers, " << kRegionBytesPerCell << " bytes per cell); give more memory";
    throw InputError(message.str());
  }
  const int border = plan.halo_cells + plan.margin_cells;
  int core = choice.size;
  if (core == 0) {
    const int side = static_cast<int>(std::floor(std::sqrt(for_tiles / kTileBytesPerCell)));
    core = side - 2 * border;
    if (core < 16) {
      std::ostringstream message;
      message << "--memory " << gigabytes(plan.memory_bytes) << ": a tile with a halo of " << choice.halo
              << " m needs at least " << gigabytes(kBaseBytes + plan.region_bytes +
                                                   std::pow(16.0 + 2 * border, 2) * kTileBytesPerCell)
              << " (" << kTileBytesPerCell << " bytes per cell of its " << 16 + 2 * border
              << " cells wide window); give more memory or a smaller --halo";
      throw InputError(message.str());
    }
  }
  if (core >= region.width && core >= region.height) {
    whole_region();
    return plan;
  }
  plan.core_cells = core;
  for (int row = 0; row < region.height; row += core) {
    for (int col = 0; col < region.width; col += core) {
      const int w = std::min(core, region.width - col), h = std::min(core, region.height - row);
      const HaloWindow around = halo_window(region, col, col + w, row, row + h, plan.halo_cells, plan.margin_cells);
      plan.tiles.push_back(Tile{region.window(col, row, w, h), around.window, around.halo_edge});
      plan.tile_bytes = std::max(plan.tile_bytes, static_cast<double>(around.window.cell_count()) * kTileBytesPerCell);
    }
  }
  return plan;
}

HaloWindow halo_window(const GridSpec& region, int col0, int col1, int row0, int row1, int halo, int margin) {
  const int border = halo + margin;
  const int c0 = std::max(0, col0 - border), c1 = std::min(region.width, col1 + border);
  const int r0 = std::max(0, row0 - border), r1 = std::min(region.height, row1 + border);
  HaloWindow out{region.window(c0, r0, c1 - c0, r1 - r0), TileBounds{}};
  // The halo's cell edges; north up, rows grow southwards, so its first row's edge is its largest y.
  const auto& gt = region.geotransform;
  if (col0 - halo > 0) out.halo_edge.x_min = gt[0] + (col0 - halo) * gt[1];
  if (col1 + halo < region.width) out.halo_edge.x_max = gt[0] + (col1 + halo) * gt[1];
  if (row0 - halo > 0) out.halo_edge.y_max = gt[3] + (row0 - halo) * gt[5];
  if (row1 + halo < region.height) out.halo_edge.y_min = gt[3] + (row1 + halo) * gt[5];
  return out;
}

std::vector<std::vector<bool>> sources_by_tile(const TilePlan& plan, const GridSpec& region,
                                               const std::vector<ReleaseSource>& sources) {
  std::vector<std::vector<bool>> selected(plan.tiles.size(), std::vector<bool>(sources.size(), false));
  if (!plan.tiled()) {
    selected.front().assign(sources.size(), true);
    return selected;
  }
  // Tiles go row by row, core_cells on a side: a source's tile follows from its cell.
  const int per_row = (region.width + plan.core_cells - 1) / plan.core_cells;
  for (std::size_t s = 0; s < sources.size(); ++s) {
    const int col = std::clamp(static_cast<int>(std::floor(region.col_of(sources[s].x) + 0.5)), 0, region.width - 1);
    const int row = std::clamp(static_cast<int>(std::floor(region.row_of(sources[s].y) + 0.5)), 0, region.height - 1);
    selected[static_cast<std::size_t>((row / plan.core_cells) * per_row + col / plan.core_cells)][s] = true;
  }
  return selected;
}

}  // namespace talus::cli
