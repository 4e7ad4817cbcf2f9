// The edge of a tile's halo (issue 19, item 4; docs/study.md, "Tiles"): where a run on a window of
// the ground stops following what it simulates, because beyond it (and its margin) the window's
// ground is not the whole DEM's. Infinite on the sides where the window reaches the DEM's edge.
#pragma once

#include <cmath>

namespace talus {

struct TileBounds {
  double x_min = -HUGE_VAL, x_max = HUGE_VAL, y_min = -HUGE_VAL, y_max = HUGE_VAL;  // m
  bool contains(double x, double y) const { return x >= x_min && x <= x_max && y >= y_min && y <= y_max; }
};

}  // namespace talus
