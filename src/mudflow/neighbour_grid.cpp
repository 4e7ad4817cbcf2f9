// Bins of the neighbour search (paper 4.1), sorted by a counting sort so the order is fixed.
#include "talus/mudflow/neighbour_grid.hpp"

#include <algorithm>
#include <limits>

namespace talus {

std::uint32_t NeighbourGrid::bin_index(double x, double y) const {
  const long col = bin_coordinate(x - origin_x_), row = bin_coordinate(y - origin_y_);
  if (col < 0 || row < 0 || col >= columns_ || row >= rows_) return std::numeric_limits<std::uint32_t>::max();
  return static_cast<std::uint32_t>(row * columns_ + col);
}

void NeighbourGrid::rebuild(const ParticleSet& particles, double bin_size) {
  const std::size_t n = particles.size();
  double largest_radius = 0;
  for (double r : particles.radius) largest_radius = std::max(largest_radius, r);
  bin_size_ = std::max(bin_size, largest_radius);
  double min_x = 0, min_y = 0, max_x = 0, max_y = 0;
  if (n > 0) {
    min_x = max_x = particles.x[0];
    min_y = max_y = particles.y[0];
  }
  for (std::size_t i = 1; i < n; ++i) {
    min_x = std::min(min_x, particles.x[i]);
    max_x = std::max(max_x, particles.x[i]);
    min_y = std::min(min_y, particles.y[i]);
    max_y = std::max(max_y, particles.y[i]);
  }
  // One bin of margin on each side, so particles that move a little stay inside the grid.
  origin_x_ = min_x - bin_size_;
  origin_y_ = min_y - bin_size_;
  columns_ = bin_coordinate(max_x - origin_x_) + 2;
  rows_ = bin_coordinate(max_y - origin_y_) + 2;

  const std::size_t bins = static_cast<std::size_t>(columns_ * rows_);
  bin_of_.resize(n);
  bin_start_.assign(bins + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    bin_of_[i] = bin_index(particles.x[i], particles.y[i]);
    ++bin_start_[bin_of_[i] + 1];
  }
  for (std::size_t b = 0; b < bins; ++b) bin_start_[b + 1] += bin_start_[b];
  std::vector<std::uint32_t> next(bin_start_.begin(), bin_start_.end() - 1);
  sorted_.resize(n);
  for (std::size_t i = 0; i < n; ++i) sorted_[next[bin_of_[i]]++] = static_cast<std::uint32_t>(i);
}

bool NeighbourGrid::update(const ParticleSet& particles) {
  bool stale = particles.size() != bin_of_.size();
  for (std::size_t i = 0; i < particles.size() && !stale; ++i) {
    stale = particles.radius[i] > bin_size_ || bin_index(particles.x[i], particles.y[i]) != bin_of_[i];
  }
  if (stale) rebuild(particles, bin_size_);
  return stale;
}

}  // namespace talus
