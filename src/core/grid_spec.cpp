// GridSpec comparison (DESIGN.md section 1: grids whose specs differ are refused when combined).
#include "talus/core/grid_spec.hpp"

#include <algorithm>
#include <cmath>

#include "talus/core/errors.hpp"

namespace talus {

bool GridSpec::same_grid(const GridSpec& other) const {
  if (width != other.width || height != other.height || crs_wkt != other.crs_wkt) return false;
  const double tolerance = 1e-9 * std::max(std::abs(geotransform[1]), std::abs(geotransform[5]));
  for (int k = 0; k < 6; ++k) {
    if (std::abs(geotransform[k] - other.geotransform[k]) > tolerance) return false;
  }
  return true;
}

bool GridSpec::cell_at(double x, double y, int& col, int& row) const {
  const double c = col_of(x), r = row_of(y);
  // The range test comes first, in floating point: NaN fails it, and inside it the rounding fits int.
  if (!(c >= -0.5 && c < width - 0.5 && r >= -0.5 && r < height - 0.5)) return false;
  col = std::clamp(static_cast<int>(std::floor(c + 0.5)), 0, width - 1);
  row = std::clamp(static_cast<int>(std::floor(r + 0.5)), 0, height - 1);
  return true;
}

void require_same_grid(const GridSpec& a, const GridSpec& b, const std::string& what) {
  if (a.same_grid(b)) return;
  throw GridMismatch(what + ": grids differ (" + std::to_string(a.width) + "x" + std::to_string(a.height) +
                     " vs " + std::to_string(b.width) + "x" + std::to_string(b.height) +
                     ", or their origin, cell size or CRS)");
}

}  // namespace talus
