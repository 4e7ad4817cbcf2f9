// CellMaxima: the largest value seen per grid cell (docs/architecture.md section 2, "Statistical maps":
// maximal kinetic energy and velocity). Stored as float, the precision of the layers; rounding
// to float is monotone, so the maximum of rounded values is the rounded maximum and merges are
// exact in any order. Every cell starts at 0 (never reached reads 0, docs/architecture.md section 3), so
// values <= 0 and NaN leave a cell unchanged: this accumulator is for non-negative quantities.
#pragma once

#include <cstddef>

#include "talus/core/byte_stream.hpp"
#include "talus/hazard/zeroed_vector.hpp"

namespace talus {

class CellMaxima {
 public:
  explicit CellMaxima(std::size_t cell_count) : maxima_(cell_count) {}

  void add(std::size_t cell, double value) {
    const float v = static_cast<float>(value);
    if (v > maxima_[cell]) maxima_[cell] = v;
  }
  // Keeps the larger value of this and `other` (same cell count) in every cell.
  void merge(const CellMaxima& other);
  // For MPI ranks (core/byte_stream.hpp): the reached cells; read() into an all-zero one.
  void write(ByteWriter& out) const { out.put_sparse(maxima_); }
  void read(ByteReader& in) { in.get_sparse(maxima_); }

  float operator[](std::size_t cell) const { return maxima_[cell]; }
  std::size_t size() const { return maxima_.size(); }

 private:
  ZeroedVector<float> maxima_;
};

}  // namespace talus
