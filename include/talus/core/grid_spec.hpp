// GridSpec: the georeferencing of a raster grid (docs/architecture.md section 1).
// The engine works in the CRS's metres and never interprets the CRS, which it carries as an
// opaque WKT string. Cells are areas: cell (col, row) covers
// [x0 + col dx, x0 + (col + 1) dx] x [y0 + (row + 1) dy, y0 + row dy] with dy < 0 (north up);
// its node, where node values such as elevation live, is the cell centre.
#pragma once

#include <array>
#include <cstddef>
#include <string>

namespace talus {

struct GridSpec {
  int width = 0;                                     // columns
  int height = 0;                                    // rows
  std::array<double, 6> geotransform{0, 1, 0, 0, 0, -1};  // GDAL order: x0, dx, 0, y0, 0, dy (m)
  std::string crs_wkt;                               // opaque; empty for local coordinates
  double nodata = -9999.0;                           // value marking cells outside the valid area
  // A tile's window of a larger grid (issue 19, item 4; docs/study.md, "Tiles"): the geotransform
  // stays the whole grid's, and cell (col, row) here is cell (col + col_offset, row + row_offset)
  // there, so that a point falls in the same cell, by the same rounding, as on the whole grid.
  // whole_width x whole_height is the whole grid's size; 0 for a grid that is whole.
  int col_offset = 0, row_offset = 0;
  int whole_width = 0, whole_height = 0;

  std::size_t cell_count() const { return static_cast<std::size_t>(width) * static_cast<std::size_t>(height); }
  double cell_width() const { return geotransform[1]; }     // m, > 0
  double cell_height() const { return -geotransform[5]; }   // m, > 0 for north-up grids
  double cell_area() const { return cell_width() * cell_height(); }  // m2
  // Centre of cell (col, row) in CRS coordinates (m).
  double node_x(double col) const { return geotransform[0] + (col + col_offset + 0.5) * geotransform[1]; }
  double node_y(double row) const { return geotransform[3] + (row + row_offset + 0.5) * geotransform[5]; }
  // Continuous cell coordinates of a point: node (col, row) sits at integer values. On a window,
  // the whole grid's coordinate less the offset: exact for points on the window.
  double col_of(double x) const { return (x - geotransform[0]) / geotransform[1] - 0.5 - col_offset; }
  double row_of(double y) const { return (y - geotransform[3]) / geotransform[5] - 0.5 - row_offset; }
  bool contains_cell(int col, int row) const { return col >= 0 && row >= 0 && col < width && row < height; }
  // The cell holding the point (x, y) (the nearest node), false when the point lies off the
  // grid or is not finite; no integer conversion can overflow (issue 18, item 2).
  bool cell_at(double x, double y, int& col, int& row) const;

  // Same size, geotransform (to 1e-9 of a cell), window and CRS: grids that can be combined cell by cell.
  bool same_grid(const GridSpec& other) const;

  bool is_window() const { return whole_width > 0; }
  // The window of cells [col, col + w) x [row, row + h) of this whole grid.
  GridSpec window(int col, int row, int w, int h) const;
  // The whole grid a window belongs to (this grid when it is whole).
  GridSpec whole() const;
  // The geotransform of this grid's own cell (0, 0), as GDAL describes a raster.
  std::array<double, 6> own_geotransform() const;
  // Flat index on the whole grid of this grid's flat index i.
  std::size_t whole_index(std::size_t i) const;
};

// Throws GridMismatch naming both grids when they cannot be combined cell by cell.
void require_same_grid(const GridSpec& a, const GridSpec& b, const std::string& what);

}  // namespace talus
