// A mud flow over a region larger than memory (issue 19, item 4; docs/study.md, "Tiles"): the flow
// runs on a window of the ground around its release, its halo (the distance the mud may run) and
// a margin (the particles' supports and the curvature span around mud at the halo's edge); mud
// that crosses the halo's edge leaves the flow there and is reported. Particles are numbered, and
// every cell computed, as on the whole grid, so the layers equal the whole run's bit for bit when
// no mud crossed the halo's edge.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "tile_plan.hpp"
#include "talus/core/tile_bounds.hpp"
#include "talus/gis/scene.hpp"
#include "talus/mudflow/mudflow_simulation.hpp"

namespace talus::cli {

struct MudflowWindow {
  std::optional<GridSpec> window;  // none: the region's ground fits, the flow runs on all of it
  TileBounds halo_edge;
  double halo = 0;                 // m
  double memory_bytes = 0, window_bytes = 0;
};

// The window for the release of `region` (load_region's scene) when the region's ground does not
// fit `choice` (or [tiles] size forces it); margin_m around the halo. InputError when even the
// window does not fit.
MudflowWindow plan_mudflow_window(const gis::Scene& region, const TileChoice& choice, double margin_m);

// The flow's layers on the window, written into layers on the whole region's grid: 0 where the
// flow did not reach, nodata where the DEM has none.
FlowLayers whole_region_layers(const FlowLayers& on_window, const Grid<double>& region_dem);

// The problem of mud that crossed the halo's edge; none when none did.
std::vector<std::string> halo_outflow_problems(const MudflowResult& result, double halo_m);

// run.json's `tiles` for a mud flow: its window, or null.
nlohmann::json window_record(const MudflowWindow& window);

}  // namespace talus::cli
