// Release set sizes (DESIGN.md section 3).
#include "talus/core/release.hpp"

namespace talus {

std::size_t ReleaseSet::cell_count() const {
  std::size_t count = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) count += depth[i] > 0.0f ? 1 : 0;
  return count;
}

double ReleaseSet::area() const { return static_cast<double>(cell_count()) * depth.spec().cell_area(); }

double ReleaseSet::volume() const {
  double sum = 0;
  for (std::size_t i = 0; i < depth.size(); ++i) sum += depth[i] > 0.0f ? static_cast<double>(depth[i]) : 0.0;
  return sum * depth.spec().cell_area();
}

}  // namespace talus
