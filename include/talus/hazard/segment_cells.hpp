// The grid cells a straight segment crosses, for the statistical map of paper 3.4 ("Gathering
// simulation data"): consecutive trajectory samples are joined by segments, and every cell a
// segment touches must be found however long the segment. An exact 2D grid walk (Amanatides
// and Woo 1987, "A fast voxel traversal algorithm for ray tracing") in cell coordinates
// u = (x - x0) / dx, v = (y - y0) / dy, where cell (col, row) is [col, col + 1) x [row, row + 1)
// (GridSpec's half-open cells; dy < 0 makes v grow southwards). A cell is crossed when it
// holds at least one point of the closed segment, so a segment through a corner visits the
// corner's own cell and one along an edge visits the cells on the edge's upper side.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include "talus/core/grid_spec.hpp"

namespace talus {

// CRS metres -> continuous cell coordinates of a north-up GridSpec (rotation terms ignored).
class CellFrame {
 public:
  explicit CellFrame(const GridSpec& spec)
      : x0_(spec.geotransform[0]), dx_(spec.geotransform[1]), y0_(spec.geotransform[3]),
        dy_(spec.geotransform[5]), col_offset_(spec.col_offset), row_offset_(spec.row_offset), width_(spec.width),
        height_(spec.height) {}
  // On a tile's window (GridSpec), the whole grid's coordinate less the window's offset.
  double u(double x) const { return (x - x0_) / dx_ - col_offset_; }
  double v(double y) const { return (y - y0_) / dy_ - row_offset_; }
  int width() const { return width_; }
  int height() const { return height_; }
  bool inside(double u, double v) const { return u >= 0 && v >= 0 && u < width_ && v < height_; }

 private:
  double x0_, dx_, y0_, dy_;
  double col_offset_, row_offset_;
  int width_, height_;
};

// floor(x) as an int for |x| < 2^31, without a library call.
inline int floor_to_int(double x) {
  const int truncated = static_cast<int>(x);
  return x < truncated ? truncated - 1 : truncated;
}

namespace segment_cells_detail {

// Narrows [t_begin, t_end] to where p + t d lies in [low, high]; false when empty.
inline bool clip(double p, double d, double low, double high, double& t_begin, double& t_end) {
  if (d == 0) return p >= low && p <= high;
  double ta = (low - p) / d;
  double tb = (high - p) / d;
  if (ta > tb) std::swap(ta, tb);
  t_begin = std::max(t_begin, ta);
  t_end = std::min(t_end, tb);
  return t_begin <= t_end;
}

// Crossing parameter of the next cell boundary along one axis.
inline double next_crossing(int cell, int step, double p, double d) {
  const double boundary = step > 0 ? cell + 1.0 : static_cast<double>(cell);
  return (boundary - p) / d;
}

}  // namespace segment_cells_detail

// Calls visit(col, row, t_enter, t_exit) for each cell of a width x height grid crossed by
// the segment (u0, v0) -> (u1, v1), in order along it, each cell once per contiguous stretch;
// t_enter <= t_exit are the segment parameters (0 at the start, 1 at the end) where the
// segment enters and leaves the cell. Parts outside the grid and non-finite segments visit
// nothing.
template <class Visit>
void walk_segment_cells(double u0, double v0, double u1, double v1, int width, int height, Visit&& visit) {
  using segment_cells_detail::clip;
  using segment_cells_detail::next_crossing;
  if (!(std::isfinite(u0) && std::isfinite(v0) && std::isfinite(u1) && std::isfinite(v1))) return;
  const double du = u1 - u0;
  const double dv = v1 - v0;
  if (!(std::isfinite(du) && std::isfinite(dv))) return;
  // Walk only the part within one cell of the grid: the walk's length stays bounded.
  double t_begin = 0.0;
  double t_end = 1.0;
  const double u_high = width + 1.0;
  const double v_high = height + 1.0;
  const bool in_margin = u0 >= -1.0 && u1 >= -1.0 && v0 >= -1.0 && v1 >= -1.0 && u0 <= u_high && u1 <= u_high &&
                         v0 <= v_high && v1 <= v_high;
  if (!in_margin && !(clip(u0, du, -1.0, u_high, t_begin, t_end) && clip(v0, dv, -1.0, v_high, t_begin, t_end))) return;
  const double ua = t_begin == 0.0 ? u0 : u0 + t_begin * du;
  const double va = t_begin == 0.0 ? v0 : v0 + t_begin * dv;
  const double ub = t_end == 1.0 ? u1 : u0 + t_end * du;
  const double vb = t_end == 1.0 ? v1 : v0 + t_end * dv;
  int col = floor_to_int(ua);
  int row = floor_to_int(va);
  const int col_end = floor_to_int(ub);
  const int row_end = floor_to_int(vb);
  const int step_col = col_end >= col ? 1 : -1;
  const int step_row = row_end >= row ? 1 : -1;
  int cols_left = std::abs(col_end - col);
  int rows_left = std::abs(row_end - row);
  double t_col = cols_left > 0 ? next_crossing(col, step_col, u0, du) : t_end;
  double t_row = rows_left > 0 ? next_crossing(row, step_row, v0, dv) : t_end;
  double t_enter = t_begin;
  while (cols_left > 0 || rows_left > 0) {
    bool move_col = rows_left == 0;
    bool move_row = cols_left == 0;
    if (cols_left > 0 && rows_left > 0) {
      if (t_col < t_row) {
        move_col = true;
      } else if (t_row < t_col) {
        move_row = true;
      } else if (step_col == step_row) {
        // Through a corner, diagonally: the corner belongs to the cell it leads into (both
        // steps up) or to the current cell (both down), never to the two side cells.
        move_col = move_row = true;
      } else {
        // Through a corner across the diagonal: the corner belongs to the side cell reached
        // by stepping up first; the downward step follows at the same parameter.
        move_col = step_col > 0;
        move_row = step_row > 0;
      }
    }
    const double t_cross = std::clamp(move_col ? t_col : t_row, t_enter, t_end);
    if (col >= 0 && row >= 0 && col < width && row < height) visit(col, row, t_enter, t_cross);
    t_enter = t_cross;
    if (move_col) {
      col += step_col;
      if (--cols_left > 0) t_col = next_crossing(col, step_col, u0, du);
    }
    if (move_row) {
      row += step_row;
      if (--rows_left > 0) t_row = next_crossing(row, step_row, v0, dv);
    }
  }
  if (col >= 0 && row >= 0 && col < width && row < height) visit(col, row, t_enter, t_end);
}

}  // namespace talus
