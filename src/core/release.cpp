// Release set sizes (docs/architecture.md section 3) and the conditions of release cells (issue 16).
#include "talus/core/release.hpp"

namespace talus {

std::size_t ReleaseSet::cell_count() const {
  std::size_t count = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) count += depth[i] > 0.0f ? 1 : 0;
  return count;
}

double ReleaseSet::area() const { return static_cast<double>(cell_count()) * depth.spec().cell_area(); }

double ReleaseSet::vertical_volume() const {
  double sum = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) sum += depth[i] > 0.0f ? static_cast<double>(depth[i]) : 0.0;
  return sum * depth.spec().cell_area();
}

ReleaseConditions ReleaseSet::cell_conditions(int col, int row) const {
  if (condition_set_of_cell.size() == 0) return {};
  const int set = condition_set_of_cell.at(col, row);
  return set > 0 ? condition_sets[static_cast<std::size_t>(set - 1)] : ReleaseConditions{};
}

std::int64_t ReleaseSet::cell_feature(int col, int row) const {
  return feature_of_cell.size() == 0 ? kNoReleaseFeature : feature_of_cell.at(col, row);
}

ReleaseSet ReleaseSet::window(const GridSpec& spec) const {
  ReleaseSet part;
  part.depth = window_of(depth, spec);
  part.points = points;
  part.condition_sets = condition_sets;
  part.depths_from_surface_lowering = depths_from_surface_lowering;
  if (condition_set_of_cell.size() > 0) part.condition_set_of_cell = window_of(condition_set_of_cell, spec);
  if (feature_of_cell.size() > 0) part.feature_of_cell = window_of(feature_of_cell, spec);
  return part;
}

}  // namespace talus
