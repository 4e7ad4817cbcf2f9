// Grid<T>: a raster of T in row-major flat storage with its GridSpec (docs/architecture.md section 1).
#pragma once

#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include "talus/core/errors.hpp"
#include "talus/core/grid_spec.hpp"

namespace talus {

template <class T>
class Grid {
 public:
  Grid() = default;
  explicit Grid(GridSpec spec, T fill = T{})
      : spec_(std::move(spec)), values_(spec_.cell_count(), fill) {}
  Grid(GridSpec spec, std::vector<T> values) : spec_(std::move(spec)), values_(std::move(values)) {
    if (values_.size() != spec_.cell_count()) throw GridMismatch("grid values do not match the grid size");
  }

  const GridSpec& spec() const { return spec_; }
  int width() const { return spec_.width; }
  int height() const { return spec_.height; }
  std::size_t size() const { return values_.size(); }

  std::size_t index(int col, int row) const {
    return static_cast<std::size_t>(row) * static_cast<std::size_t>(spec_.width) + static_cast<std::size_t>(col);
  }
  T& at(int col, int row) { return values_[index(col, row)]; }
  const T& at(int col, int row) const { return values_[index(col, row)]; }
  T& operator[](std::size_t i) { return values_[i]; }
  const T& operator[](std::size_t i) const { return values_[i]; }

  // A cell is valid when it holds a finite value other than the spec's nodata.
  bool is_valid(std::size_t i) const {
    const double v = static_cast<double>(values_[i]);
    return std::isfinite(v) && v != spec_.nodata;
  }
  bool is_valid(int col, int row) const { return spec_.contains_cell(col, row) && is_valid(index(col, row)); }

  std::vector<T>& values() { return values_; }
  const std::vector<T>& values() const { return values_; }

 private:
  GridSpec spec_;
  std::vector<T> values_;
};

// The values of a whole grid on one of its windows (GridSpec::window; issue 19, item 4).
template <class T>
Grid<T> window_of(const Grid<T>& whole, const GridSpec& window) {
  if (!window.is_window() || !window.whole().same_grid(whole.spec())) throw GridMismatch("window_of: not a window of this grid");
  GridSpec spec = window;
  spec.nodata = whole.spec().nodata;
  Grid<T> part(spec);
  for (int row = 0; row < window.height; ++row) {
    for (int col = 0; col < window.width; ++col) part.at(col, row) = whole.at(col + window.col_offset, row + window.row_offset);
  }
  return part;
}

// Writes a window's values into the whole grid it is a window of.
template <class T>
void paste_window(Grid<T>& whole, const Grid<T>& part) {
  const GridSpec& window = part.spec();
  if (!window.is_window() || !window.whole().same_grid(whole.spec())) throw GridMismatch("paste_window: not a window of this grid");
  for (int row = 0; row < window.height; ++row) {
    for (int col = 0; col < window.width; ++col) whole.at(col + window.col_offset, row + window.row_offset) = part.at(col, row);
  }
}

// Applies f(a[i], b[i]) cell by cell into a grid on a's spec; refuses grids whose specs differ.
template <class A, class B, class F>
auto combine(const Grid<A>& a, const Grid<B>& b, F f, const std::string& what) {
  require_same_grid(a.spec(), b.spec(), what);
  using R = decltype(f(a[0], b[0]));
  Grid<R> out(a.spec());
  for (std::size_t i = 0; i < a.size(); ++i) out[i] = f(a[i], b[i]);
  return out;
}

}  // namespace talus
