// A mud flow on a window of the region (mudflow_window.hpp; issue 19, item 4).
#include "mudflow_window.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "talus/core/errors.hpp"

namespace talus::cli {
namespace {

// The layer on the whole grid: 0 on valid terrain, nodata elsewhere, the window's values on it.
Grid<float> whole_layer(const Grid<float>& on_window, const Grid<double>& region_dem) {
  GridSpec spec = region_dem.spec();
  spec.nodata = on_window.spec().nodata;
  Grid<float> whole(spec, 0.0f);
  for (std::size_t cell = 0; cell < whole.size(); ++cell) {
    if (!region_dem.is_valid(cell)) whole[cell] = static_cast<float>(spec.nodata);
  }
  paste_window(whole, on_window);
  return whole;
}

}  // namespace

MudflowWindow plan_mudflow_window(const gis::Scene& region, const TileChoice& choice, double margin_m) {
  const GridSpec& grid = region.dem.elevation.spec();
  const TilePlan plan = plan_tiles(grid, TileChoice{choice.memory, 0, choice.size}, 0);
  MudflowWindow result;
  result.halo = choice.halo;
  result.memory_bytes = plan.memory_bytes;
  if (!plan.tiled()) return result;
  // The release's cells and points, in cells of the whole grid.
  const ReleaseSet& release = *region.release;
  int col0 = grid.width, col1 = -1, row0 = grid.height, row1 = -1;
  const auto include = [&](int col, int row) {
    col0 = std::min(col0, col);
    col1 = std::max(col1, col);
    row0 = std::min(row0, row);
    row1 = std::max(row1, row);
  };
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col < grid.width; ++col) {
      if (release.depth.at(col, row) > 0.0f) include(col, row);
    }
  }
  for (const ReleasePoint& point : release.points) {
    int col = 0, row = 0;
    if (grid.cell_at(point.x, point.y, col, row)) include(col, row);
  }
  if (col1 < 0) return result;  // nothing to release: the run says so on the whole grid
  const double cell = std::min(grid.cell_width(), grid.cell_height());
  const int halo = static_cast<int>(std::ceil(choice.halo / cell));
  const HaloWindow around =
      halo_window(grid, col0, col1 + 1, row0, row1 + 1, halo, static_cast<int>(std::ceil(margin_m / cell)) + 2);
  result.window = around.window;
  result.halo_edge = around.halo_edge;
  result.window_bytes = static_cast<double>(result.window->cell_count()) * kTileBytesPerCell;
  if (kBaseBytes + plan.region_bytes + result.window_bytes > plan.memory_bytes && choice.size == 0) {
    std::ostringstream halo_text;  // the halo as given, the sizes to 3 digits
    halo_text << choice.halo;
    std::ostringstream message;
    message.precision(3);
    message << "--memory " << plan.memory_bytes / 1e9 << " GB: the mud flow's window (its release and a halo of "
            << halo_text.str() << " m, " << result.window->width << " x " << result.window->height << " cells) needs about "
            << (kBaseBytes + plan.region_bytes + result.window_bytes) / 1e9 << " GB; give more memory or a smaller --halo";
    throw InputError(message.str());
  }
  return result;
}

FlowLayers whole_region_layers(const FlowLayers& on_window, const Grid<double>& region_dem) {
  FlowLayers whole;
  whole.flow_depth_max = whole_layer(on_window.flow_depth_max, region_dem);
  whole.velocity_max = whole_layer(on_window.velocity_max, region_dem);
  whole.pressure_max = whole_layer(on_window.pressure_max, region_dem);
  whole.deposit_depth = whole_layer(on_window.deposit_depth, region_dem);
  whole.arrival_time = whole_layer(on_window.arrival_time, region_dem);
  if (on_window.erosion_depth) whole.erosion_depth = whole_layer(*on_window.erosion_depth, region_dem);
  return whole;
}

std::vector<std::string> halo_outflow_problems(const MudflowResult& result, double halo_m) {
  if (!(result.halo_outflow_volume > 0.0)) return {};
  std::ostringstream line;
  line.precision(3);
  line << "mud flow: " << result.halo_outflow_volume << " m3 ("
       << 100.0 * result.halo_outflow_volume / std::max(result.released_volume + result.entrained_volume, 1e-300)
       << " % of the released and entrained volume) crossed the edge of the flow's window ([tiles] halo = " << halo_m
       << " m beyond its release) and left the flow there; the layers miss where it went: raise --halo";
  return {line.str()};
}

nlohmann::json window_record(const MudflowWindow& window) {
  if (!window.window) return nullptr;
  return {{"window_cells", {window.window->width, window.window->height}},
          {"window_offset_cells", {window.window->col_offset, window.window->row_offset}},
          {"halo_m", window.halo},
          {"memory_gb", window.memory_bytes / 1e9},
          {"estimated_window_gb", window.window_bytes / 1e9}};
}

}  // namespace talus::cli
