// Neighbour search for the particles (paper 4.1): a uniform grid of square bins over the
// horizontal plane, with particle indices sorted by bin so every query visits candidates in the
// same order whatever the thread count. update() re-bins only when some particle has left its
// bin or the bin size must change, so the grid follows the flow incrementally.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "talus/mudflow/particle_set.hpp"

namespace talus {

class NeighbourGrid {
 public:
  // Bins every particle; bins are squares of side `bin_size` (m), at least the largest support
  // radius so a query of that range looks at 3 x 3 bins.
  void rebuild(const ParticleSet& particles, double bin_size);
  // Re-bins when a particle changed bin, the count changed, or the largest support radius
  // exceeds the bin size; returns true when it did.
  bool update(const ParticleSet& particles);

  double bin_size() const { return bin_size_; }
  std::size_t particle_count() const { return bin_of_.size(); }

  // Calls visit(j) for every particle j (i itself included) whose horizontal distance to
  // (x, y) may be below `range` (m, at most bin_size()), in ascending bin then index order.
  // Candidates are not filtered by distance: the caller computes it.
  template <class Visit>
  void for_each_candidate(double x, double y, double range, Visit&& visit) const {
    const long reach = range <= bin_size_ ? 1 : static_cast<long>(std::ceil(range / bin_size_));
    const long bx = bin_coordinate(x - origin_x_), by = bin_coordinate(y - origin_y_);
    for (long row = by - reach; row <= by + reach; ++row) {
      if (row < 0 || row >= rows_) continue;
      for (long col = bx - reach; col <= bx + reach; ++col) {
        if (col < 0 || col >= columns_) continue;
        const std::size_t bin = static_cast<std::size_t>(row * columns_ + col);
        for (std::uint32_t k = bin_start_[bin]; k < bin_start_[bin + 1]; ++k) visit(sorted_[k]);
      }
    }
  }

 private:
  long bin_coordinate(double offset) const { return static_cast<long>(std::floor(offset / bin_size_)); }
  std::uint32_t bin_index(double x, double y) const;

  double bin_size_ = 1;              // m
  double origin_x_ = 0, origin_y_ = 0;  // m: lower-left corner of bin (0, 0)
  long columns_ = 0, rows_ = 0;
  std::vector<std::uint32_t> bin_start_;  // per bin, first slot in sorted_; one extra at the end
  std::vector<std::uint32_t> sorted_;     // particle indices by bin, ascending within a bin
  std::vector<std::uint32_t> bin_of_;     // per particle, its bin at the last rebuild
};

}  // namespace talus
