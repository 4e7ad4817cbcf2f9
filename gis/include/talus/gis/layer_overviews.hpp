// Overviews that read true at every scale (issue 17, item 4): GDAL's averaging overviews lower a
// cell's maximum as soon as one screen pixel covers several cells, so a zoomed-out or printed
// hazard map drops classes. Talus fills each overview itself, from the full-resolution cells the
// overview cell covers, with the reduction that keeps the layer's meaning (docs/layers.md,
// "Overviews").
#pragma once

#include <vector>

#include "talus/core/grid.hpp"

namespace talus::gis {

enum class OverviewReduction {
  largest,            // the largest valid value: maxima, quantiles, counts, probabilities, depths, losses
  earliest_positive,  // the smallest value above 0, else 0: arrival times, where 0 means never reached
};

// The decimation factors 2, 4, 8, ... of the overviews of a width x height layer with square
// tiles of `tile` cells: halving until the coarsest overview fits one tile (the rule of GDAL's
// COG driver, OVERVIEWS=AUTO); none for a layer that fits one tile.
std::vector<int> overview_factors(int width, int height, int tile);

// The overview of `values` by `factor`: ceil(width / factor) x ceil(height / factor) cells, each
// the reduction of the valid cells of its block, or `nodata` where the block holds none.
std::vector<float> reduced_overview(const Grid<float>& values, int factor, OverviewReduction reduction, float nodata);

}  // namespace talus::gis
