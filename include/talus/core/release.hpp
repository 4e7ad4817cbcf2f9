// Where material is released (docs/architecture.md section 3, --release): cells from a raster or
// polygons, and points. Rock fall starts one source per cell or point, with the conditions its
// feature gives (release_conditions.hpp); mud flow releases the cells' depth.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "talus/core/grid.hpp"
#include "talus/core/release_conditions.hpp"

namespace talus {

// The feature id of a release that does not come from a vector feature (a raster cell).
inline constexpr std::int64_t kNoReleaseFeature = -1;

struct ReleasePoint {
  double x = 0, y = 0;           // m, in the DEM's CRS
  double depth = 0;              // m, from a `depth` attribute (0 when none)
  ReleaseConditions conditions;  // rock fall: what the point's attributes give
  std::int64_t feature_id = kNoReleaseFeature;  // FID of the vector feature it comes from
};

struct ReleaseSet {
  Grid<float> depth;                 // m on the DEM grid: > 0 in release cells, 0 elsewhere
  std::vector<ReleasePoint> points;  // point sources
  // Rock fall, when release polygons or the bands of a release raster carry attributes: the
  // distinct sets of conditions (one per polygon, or per raster cell), and per cell the 1-based
  // index of its set (0: none). Both empty otherwise.
  std::vector<ReleaseConditions> condition_sets;
  Grid<int> condition_set_of_cell;
  // A vector release: per cell the FID of the polygon that covers it (kNoReleaseFeature: none),
  // so that results join to the release layer. Empty for a raster release.
  Grid<std::int64_t> feature_of_cell;
  // A raster release whose every depth was a negative number: the surface lowering of a DEM of
  // difference (post-event minus pre-event), whose depths are vertical (docs/inputs.md, "How a
  // mud-flow depth is measured"). The depths above are their magnitudes.
  bool depths_from_surface_lowering = false;

  std::size_t cell_count() const;    // cells with depth > 0
  double area() const;               // m2 covered by release cells
  double vertical_volume() const;    // m3: sum of depth x cell area, the depths taken as vertical
  std::size_t source_count() const { return cell_count() + points.size(); }
  ReleaseConditions cell_conditions(int col, int row) const;  // those of the cell's set (empty: none)
  std::int64_t cell_feature(int col, int row) const;          // the covering polygon's FID, or kNoReleaseFeature

  // The release on a window of its grid (GridSpec::window; issue 19, item 4): the cells' grids cut
  // to it, every point kept.
  ReleaseSet window(const GridSpec& spec) const;
};

}  // namespace talus
