// Radius classes and their bins (paper 4.1 neighbour search; pair_search.hpp), sorted by a
// counting sort so the order is fixed.
#include "talus/mudflow/pair_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "talus/mudflow/particle_parts.hpp"

namespace talus {
namespace {

// Radii up to R0 2^kMostClasses get a class of their own; wider ones share the last (its reach
// is then raised to their largest radius).
constexpr int kMostClasses = 24;
constexpr std::size_t kPossibleClasses = kMostClasses + 1;

// Bins across the reach of a class (-): narrower bins follow a query's circle more closely, so
// it reads fewer candidates, but it visits more rows of bins, and each row ends its loop with a
// branch the processor mispredicts.
constexpr double kBinsPerReach = 2.0;
// Bins per particle of a class at most (-): the bins cost memory and a pass per rebuild, so a
// class of few particles spread far apart gets wider bins. The bin size changes only how many
// candidates a query reads, never which pairs it finds.
constexpr double kMostBinsPerParticle = 2.0;
// Margin (in bins) by which a query widens its reach, far above the rounding of the bin
// coordinates, so that a particle on a bin's edge is never missed.
constexpr double kBinMargin = 1e-4;

int class_of(double radius, double smallest_radius) {
  int k = 0;
  double bound = smallest_radius;
  while (radius > bound && k < kMostClasses) {
    bound *= 2.0;
    ++k;
  }
  return k;
}

// Bin coordinate of `offset` (m) from the origin, clamped to [0, count - 1].
long clamped_bin(double offset, double bin, long count) {
  const double b = std::floor(offset / bin);
  if (b < 0.0) return 0;
  if (b >= static_cast<double>(count - 1)) return count - 1;
  return static_cast<long>(b);
}

}  // namespace

void PairSearch::rebuild(const ParticleSet& particles, const std::vector<double>& radii, double smallest_radius,
                         int threads) {
  const std::size_t n = particles.size();
  class_index_.resize(n);
  bin_of_.resize(n);
  const std::size_t parts = static_cast<std::size_t>(std::max(threads, 1));
  part_bounds_.assign(parts * kPossibleClasses, ClassBounds{});

  // The particles' classes and, per part, each class's bounds.
  for_each_part(n, parts, [&](std::size_t part, std::size_t first, std::size_t last) {
    ClassBounds* bounds = part_bounds_.data() + part * kPossibleClasses;
    for (std::size_t i = first; i < last; ++i) {
      const int k = class_of(radii[i], smallest_radius);
      class_index_[i] = static_cast<std::uint8_t>(k);
      bounds[k].add(particles.x[i], particles.y[i], radii[i]);
    }
  });
  ClassBounds bounds[kPossibleClasses];  // of every class, whole
  std::size_t class_count = 0;
  for (std::size_t k = 0; k < kPossibleClasses; ++k) {
    for (std::size_t part = 0; part < parts; ++part) bounds[k].merge(part_bounds_[part * kPossibleClasses + k]);
    if (bounds[k].members > 0) class_count = k + 1;
  }

  classes_.resize(class_count);  // each class keeps its bins' storage from the last rebuild
  std::vector<std::size_t> first_bin(class_count + 1, 0);  // the classes' bins, end to end
  for (std::size_t k = 0; k < class_count; ++k) {
    RadiusClass& c = classes_[k];
    const ClassBounds& b = bounds[k];
    first_bin[k + 1] = first_bin[k];
    c.columns = c.rows = 0;
    c.start.clear();
    if (b.members == 0) continue;
    c.reach = std::max(std::ldexp(smallest_radius, static_cast<int>(k)), b.widest);
    const double width = b.max_x - b.min_x, height = b.max_y - b.min_y;
    const double sparse = std::sqrt(width * height / (kMostBinsPerParticle * static_cast<double>(b.members)));
    c.bin = std::max(c.reach / kBinsPerReach, sparse);
    c.origin_x = b.min_x;
    c.origin_y = b.min_y;
    c.columns = static_cast<long>(width / c.bin) + 1;
    c.rows = static_cast<long>(height / c.bin) + 1;
    const std::size_t bins = static_cast<std::size_t>(c.columns * c.rows);
    c.start.assign(bins + 1, 0);
    first_bin[k + 1] = first_bin[k] + bins;
  }

  // Counting sort by (class, bin), stable in the particle index: each part counts its particles
  // per bin, and a bin holds the particles of one part after those of the parts before it.
  const std::size_t all_bins = first_bin.back();
  part_counts_.assign(parts * all_bins, 0);
  for_each_part(n, parts, [&](std::size_t part, std::size_t first, std::size_t last) {
    std::uint32_t* counts = part_counts_.data() + part * all_bins;
    for (std::size_t i = first; i < last; ++i) {
      const std::size_t k = class_index_[i];
      const RadiusClass& c = classes_[k];
      const long column = clamped_bin(particles.x[i] - c.origin_x, c.bin, c.columns);
      const long row = clamped_bin(particles.y[i] - c.origin_y, c.bin, c.rows);
      bin_of_[i] = static_cast<std::uint32_t>(row * c.columns + column);
      ++counts[first_bin[k] + bin_of_[i]];
    }
  });
  // Each bin's first slot, and each part's first slot in it.
  std::uint32_t slot = 0;
  for (std::size_t k = 0; k < class_count; ++k) {
    std::vector<std::uint32_t>& start = classes_[k].start;
    if (start.empty()) continue;
    for (std::size_t b = 0; b + 1 < start.size(); ++b) {
      start[b] = slot;
      for (std::size_t part = 0; part < parts; ++part) {
        std::uint32_t& count = part_counts_[part * all_bins + first_bin[k] + b];
        const std::uint32_t members = count;
        count = slot;
        slot += members;
      }
    }
    start.back() = slot;
  }

  index_.resize(n);
  x_.resize(n);
  y_.resize(n);
  radius_.resize(n);
  radius2_.resize(n);
  inverse_.resize(n);
  mass_.resize(n);
  slot_.resize(n);
  for_each_part(n, parts, [&](std::size_t part, std::size_t first, std::size_t last) {
    std::uint32_t* next_slot = part_counts_.data() + part * all_bins;
    for (std::size_t i = first; i < last; ++i) {
      const std::uint32_t at = next_slot[first_bin[class_index_[i]] + bin_of_[i]]++;
      index_[at] = static_cast<std::uint32_t>(i);
      slot_[i] = at;
      x_[at] = particles.x[i];
      y_[at] = particles.y[i];
      radius_[at] = radii[i];
      radius2_[at] = radii[i] * radii[i];
      inverse_[at] = 1.0 / radii[i];
      mass_[at] = particles.mass[i];
    }
  });
}

std::span<const std::uint32_t> PairSearch::find_pairs(double x, double y, double radius, std::uint32_t self) const {
  // Every slot is read at most once per query, so storage for all of them always suffices.
  thread_local std::vector<std::uint32_t> pairs;
  if (pairs.size() < index_.size()) pairs.resize(index_.size());
  const std::uint32_t self_slot = self < slot_.size() ? slot_[self] : std::numeric_limits<std::uint32_t>::max();
  std::size_t count = 0;
  for (const RadiusClass& c : classes_) {
    if (c.columns > 0) count = scan_class(c, x, y, radius, self_slot, pairs.data(), count);
  }
  return {pairs.data(), count};
}

// The bins of one class within max(radius, class reach) of (x, y), row by row: the pairs' slots
// go to pairs[count...]; returns the new count. A row of bins is a contiguous range of slots,
// filtered without branches (about half the candidates lie beyond the support, a branch the
// processor cannot predict); the query's own slot splits its row in two.
std::size_t PairSearch::scan_class(const RadiusClass& c, double x, double y, double radius, std::uint32_t self_slot,
                                   std::uint32_t* pairs, std::size_t count) const {
  const double margin = kBinMargin * c.bin;  // m
  const double reach = std::max(radius, c.reach) + margin;
  const double offset_x = x - c.origin_x, offset_y = y - c.origin_y;  // m
  const double extent_x = static_cast<double>(c.columns) * c.bin, extent_y = static_cast<double>(c.rows) * c.bin;
  if (offset_x + reach < 0.0 || offset_y - reach > extent_y || offset_y + reach < 0.0 || offset_x - reach > extent_x) {
    return count;
  }
  const long first_column = clamped_bin(offset_x - reach, c.bin, c.columns);
  const long last_column = clamped_bin(offset_x + reach, c.bin, c.columns);
  const long first_row = clamped_bin(offset_y - reach, c.bin, c.rows);
  const long last_row = clamped_bin(offset_y + reach, c.bin, c.rows);
  const double radius2 = radius * radius;
  const double* px = x_.data();
  const double* py = y_.data();
  const double* pr2 = radius2_.data();
  const auto filter = [&](std::uint32_t from, std::uint32_t to) {
    for (std::uint32_t s = from; s < to; ++s) {
      const double dx = x - px[s], dy = y - py[s];
      const double r2 = dx * dx + dy * dy;
      pairs[count] = s;
      count += static_cast<std::size_t>(r2 < std::max(radius2, pr2[s]));
    }
  };
  for (long row = first_row; row <= last_row; ++row) {
    const std::uint32_t from = c.start[static_cast<std::size_t>(row * c.columns + first_column)];
    const std::uint32_t to = c.start[static_cast<std::size_t>(row * c.columns + last_column + 1)];
    if (self_slot >= from && self_slot < to) {
      filter(from, self_slot);
      filter(self_slot + 1, to);
    } else {
      filter(from, to);
    }
  }
  return count;
}

}  // namespace talus
