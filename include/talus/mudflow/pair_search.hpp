// Exact search of the interacting pairs when smoothing radii differ (paper 4.1 with the variable
// radii of flow_density.hpp): i and j interact when their horizontal distance r is below
// max(R_i, R_j), so a narrow particle must also find the wide ones that reach it.
//
// Particles are sorted into radius classes: class k holds the radii in (R0 2^(k-1), R0 2^k]
// (class 0 every radius up to R0), each class in its own grid of square bins of side
// R0 2^(k-1). A query with radius R visits, in each class, the bins within max(R, R0 2^k) of the
// point: every pair lies there whichever of the two particles is wider. So each particle finds
// all its pairs by itself, whether its neighbours are being evaluated or are between their own
// steps, and a fine particle beside a coarse one scans fine bins, not coarse ones.
//
// The classes keep copies of the positions, radii and masses in bin order, so a query reads
// contiguous memory; a row of bins is one contiguous range, filtered without branches. Every
// query lists its pairs in the same fixed order (class, row, column, particle index), whatever
// the thread count.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "talus/mudflow/particle_set.hpp"

namespace talus {

class PairSearch {
 public:
  // Sorts every particle into its radius class and bin. radii[i] is particle i's radius (m);
  // smallest_radius is R0 (m), the upper bound of class 0. On up to `threads` threads, each
  // sorting a contiguous part of the particles; the slots are the same for any count.
  void rebuild(const ParticleSet& particles, const std::vector<double>& radii, double smallest_radius,
               int threads = 1);

  // The slot of every particle j != self with (x_j - x)^2 + (y_j - y)^2 < max(radius, R_j)^2, in
  // the fixed order, in storage of the calling thread that the thread's next query overwrites.
  std::span<const std::uint32_t> find_pairs(double x, double y, double radius, std::uint32_t self) const;

  // What a slot holds: the particle's index, horizontal position (m), radius (m), its inverse
  // (1/m) and mass (kg) at the last rebuild.
  std::uint32_t index(std::uint32_t slot) const { return index_[slot]; }
  double x(std::uint32_t slot) const { return x_[slot]; }
  double y(std::uint32_t slot) const { return y_[slot]; }
  double radius(std::uint32_t slot) const { return radius_[slot]; }
  double inverse_radius(std::uint32_t slot) const { return inverse_[slot]; }
  double mass(std::uint32_t slot) const { return mass_[slot]; }

  // The slot arrays themselves, for loops over many pairs.
  struct SlotArrays {
    const std::uint32_t* index;
    const double *x, *y, *inverse_radius, *mass;
  };
  SlotArrays slot_arrays() const { return {index_.data(), x_.data(), y_.data(), inverse_.data(), mass_.data()}; }

 private:
  struct RadiusClass {
    double reach = 0;                 // m: R0 2^k, the largest radius in the class
    double bin = 0;                   // m: side of a bin
    double origin_x = 0, origin_y = 0;  // m: lower-left corner of bin (0, 0)
    long columns = 0, rows = 0;
    std::vector<std::uint32_t> start;  // per bin, its first slot; one extra at the end
  };

  // The extent (m), widest radius (m) and count of a class's particles, or of a part of them.
  struct ClassBounds {
    double min_x = std::numeric_limits<double>::infinity(), min_y = std::numeric_limits<double>::infinity();
    double max_x = -std::numeric_limits<double>::infinity(), max_y = -std::numeric_limits<double>::infinity();
    double widest = 0;
    std::size_t members = 0;
    void add(double x, double y, double radius) {
      min_x = std::min(min_x, x);
      max_x = std::max(max_x, x);
      min_y = std::min(min_y, y);
      max_y = std::max(max_y, y);
      widest = std::max(widest, radius);
      ++members;
    }
    void merge(const ClassBounds& other) {
      min_x = std::min(min_x, other.min_x);
      max_x = std::max(max_x, other.max_x);
      min_y = std::min(min_y, other.min_y);
      max_y = std::max(max_y, other.max_y);
      widest = std::max(widest, other.widest);
      members += other.members;
    }
  };

  std::size_t scan_class(const RadiusClass& c, double x, double y, double radius, std::uint32_t self_slot,
                         std::uint32_t* pairs, std::size_t count) const;

  std::vector<RadiusClass> classes_;
  std::vector<std::uint32_t> index_;  // per slot, in class then bin then index order
  std::vector<double> x_, y_, radius_, inverse_, mass_;
  std::vector<double> radius2_;       // m2: per slot, the squared radius
  std::vector<std::uint32_t> slot_;   // per particle, its slot
  // Work arrays of rebuild, kept so that the rebuild at every substep does not allocate.
  std::vector<std::uint8_t> class_index_;  // per particle
  std::vector<std::uint32_t> bin_of_;      // per particle, its bin within its class
  std::vector<ClassBounds> part_bounds_;   // per part of the particles, per possible class
  std::vector<std::uint32_t> part_counts_; // per part, per bin of all classes: count, then next free slot
};

}  // namespace talus
