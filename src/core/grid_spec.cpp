// GridSpec comparison (docs/architecture.md section 1: grids whose specs differ are refused when combined).
#include "talus/core/grid_spec.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "talus/core/errors.hpp"

namespace talus {

bool GridSpec::same_grid(const GridSpec& other) const {
  if (width != other.width || height != other.height || crs_wkt != other.crs_wkt) return false;
  if (col_offset != other.col_offset || row_offset != other.row_offset || whole_width != other.whole_width ||
      whole_height != other.whole_height) {
    return false;
  }
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

GridSpec GridSpec::window(int col, int row, int w, int h) const {
  if (is_window() || col < 0 || row < 0 || w < 1 || h < 1 || col + w > width || row + h > height) {
    throw std::invalid_argument("GridSpec::window: not a window of this grid");
  }
  GridSpec out = *this;
  out.width = w;
  out.height = h;
  out.col_offset = col;
  out.row_offset = row;
  out.whole_width = width;
  out.whole_height = height;
  return out;
}

GridSpec GridSpec::whole() const {
  if (!is_window()) return *this;
  GridSpec out = *this;
  out.width = whole_width;
  out.height = whole_height;
  out.col_offset = out.row_offset = out.whole_width = out.whole_height = 0;
  return out;
}

std::array<double, 6> GridSpec::own_geotransform() const {
  std::array<double, 6> gt = geotransform;
  if (col_offset != 0) gt[0] += col_offset * gt[1];
  if (row_offset != 0) gt[3] += row_offset * gt[5];
  return gt;
}

std::size_t GridSpec::whole_index(std::size_t i) const {
  if (!is_window()) return i;
  const std::size_t w = static_cast<std::size_t>(width);
  return (i / w + static_cast<std::size_t>(row_offset)) * static_cast<std::size_t>(whole_width) + i % w +
         static_cast<std::size_t>(col_offset);
}

void require_same_grid(const GridSpec& a, const GridSpec& b, const std::string& what) {
  if (a.same_grid(b)) return;
  throw GridMismatch(what + ": grids differ (" + std::to_string(a.width) + "x" + std::to_string(a.height) +
                     " vs " + std::to_string(b.width) + "x" + std::to_string(b.height) +
                     ", or their origin, cell size or CRS)");
}

}  // namespace talus
