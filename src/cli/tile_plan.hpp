// Regions larger than memory (issue 19, item 4; docs/study.md, "Tiles"): the DEM grid cut into
// square tiles. A tile releases the rocks of the sources in its core and runs them on a window of
// the ground that adds a halo, where its rocks may go, and a margin, where the trajectory models
// may look around a rock that stands at the halo's edge; a rock that reaches the halo's edge
// stops there (StopReason::tile_edge) and is reported.
#pragma once

#include <cstddef>
#include <vector>

#include "talus/core/grid_spec.hpp"
#include "talus/core/tile_bounds.hpp"
#include "talus/rockfall/monte_carlo.hpp"

namespace talus::cli {

// What the user chooses ([tiles] in a scenario or study file; --memory, --halo, --tile-size).
struct TileChoice {
  double memory = 0;      // GB the run may use; 0: half of this machine's memory
  double halo = 2000;     // m beyond a tile's core that its rocks may reach (Tirol: some pass 1 km)
  int size = 0;           // cells on a side of a tile's core; 0: the largest that memory allows
};

struct Tile {
  GridSpec core;          // window of the region: the cells whose sources the tile releases
  GridSpec window;        // core, halo and margin, clipped to the region: the tile's ground
  TileBounds halo_edge;   // m: infinite on the sides where the tile reaches the region's edge
};

// The cells [col0, col1) x [row0, row1) of `region` grown by `halo` cells: the halo's edge (m,
// infinite where it passes the region's edge), and the window that adds `margin` cells more,
// clipped to the region. For a tile's core, and for a mud flow's release.
struct HaloWindow {
  GridSpec window;
  TileBounds halo_edge;
};
HaloWindow halo_window(const GridSpec& region, int col0, int col1, int row0, int row1, int halo, int margin);

struct TilePlan {
  std::vector<Tile> tiles;      // row by row; one tile: the run is not tiled
  int core_cells = 0;           // cells on a side of a tile's core (the last row and column may be narrower)
  double memory_bytes = 0;      // the budget the plan fits
  double tile_bytes = 0;        // the largest window's estimated bytes
  double region_bytes = 0;      // the estimated bytes of what the region holds whole
  int halo_cells = 0, margin_cells = 0;
  bool tiled() const { return tiles.size() > 1; }
};

// Estimated bytes per cell (measured, docs/performance.md "Tiles"): of a tile's window (the
// ground model with every node's material, the aligned lithology and vegetation and GDAL's
// buffers while they are read), and of the region held whole (the DEM's elevations, the release,
// the statistics' per-cell indices and the layers written at the end).
inline constexpr double kTileBytesPerCell = 200;
inline constexpr double kRegionBytesPerCell = 160;
// Bytes a run takes whatever its size (the program, GDAL, PROJ and the threads' stacks).
inline constexpr double kBaseBytes = 80e6;

// The tiles of `region` for `choice`, with a margin of margin_m metres around each halo; throws
// InputError when the region or the smallest tile does not fit the memory asked for.
TilePlan plan_tiles(const GridSpec& region, const TileChoice& choice, double margin_m);

// Per tile, which of the sources (x, y in m) lie in its core (sources off the grid go to the
// nearest tile): by source index, for SourceShare::unit.
std::vector<std::vector<bool>> sources_by_tile(const TilePlan& plan, const GridSpec& region,
                                               const std::vector<ReleaseSource>& sources);

}  // namespace talus::cli
