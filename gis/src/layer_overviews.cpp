// Overviews by the layer's own reduction (layer_overviews.hpp; docs/layers.md, "Overviews").
#include "talus/gis/layer_overviews.hpp"

#include <algorithm>

namespace talus::gis {
namespace {

int ceil_div(int value, int divisor) { return (value + divisor - 1) / divisor; }

// Reduction of one value into a block's running result; `empty` until the block has a valid cell.
struct Reducer {
  OverviewReduction reduction;
  bool empty = true;
  float result = 0.0f;

  void take(float value) {
    if (reduction == OverviewReduction::largest) {
      result = empty ? value : std::max(result, value);
    } else if (value > 0.0f) {
      result = (empty || result <= 0.0f) ? value : std::min(result, value);
    } else if (empty) {
      result = value;
    }
    empty = false;
  }
};

}  // namespace

std::vector<int> overview_factors(int width, int height, int tile) {
  std::vector<int> factors;
  for (int factor = 2; ceil_div(width, factor / 2) > tile || ceil_div(height, factor / 2) > tile; factor *= 2) {
    factors.push_back(factor);
  }
  return factors;
}

std::vector<float> reduced_overview(const Grid<float>& values, int factor, OverviewReduction reduction, float nodata) {
  const GridSpec& spec = values.spec();
  const int columns = ceil_div(spec.width, factor), rows = ceil_div(spec.height, factor);
  std::vector<float> overview(static_cast<std::size_t>(columns) * static_cast<std::size_t>(rows), nodata);
  for (int row = 0; row < rows; ++row) {
    for (int column = 0; column < columns; ++column) {
      Reducer block{reduction};
      const int last_row = std::min(spec.height, (row + 1) * factor);
      const int last_column = std::min(spec.width, (column + 1) * factor);
      for (int r = row * factor; r < last_row; ++r) {
        for (int c = column * factor; c < last_column; ++c) {
          const std::size_t cell = values.index(c, r);
          if (values.is_valid(cell)) block.take(values.at(c, r));
        }
      }
      if (!block.empty) overview[static_cast<std::size_t>(row) * static_cast<std::size_t>(columns) + column] = block.result;
    }
  }
  return overview;
}

}  // namespace talus::gis
