// CellCounts: an integer count per grid cell (docs/architecture.md section 2, "Statistical maps", and
// paper 3.4 "Gathering simulation data": passages and deposits). Additions saturate at the
// largest uint32 instead of wrapping; saturating addition of non-negative integers is
// associative, so merged counts are exact and independent of the merge order.
#pragma once

#include <cstddef>
#include <cstdint>
#include <limits>

#include "talus/core/byte_stream.hpp"
#include "talus/hazard/zeroed_vector.hpp"

namespace talus {

class CellCounts {
 public:
  explicit CellCounts(std::size_t cell_count) : counts_(cell_count) {}

  void add(std::size_t cell, std::uint32_t n = 1) { counts_[cell] = saturating_sum(counts_[cell], n); }
  // Adds every cell of `other` (same cell count) into this one.
  void merge(const CellCounts& other);
  // For MPI ranks (core/byte_stream.hpp): the non-zero cells; read() into an all-zero one.
  void write(ByteWriter& out) const { out.put_sparse(counts_); }
  void read(ByteReader& in) { in.get_sparse(counts_); }

  std::uint32_t operator[](std::size_t cell) const { return counts_[cell]; }
  std::size_t size() const { return counts_.size(); }

  static std::uint32_t saturating_sum(std::uint32_t a, std::uint32_t b) {
    constexpr std::uint32_t top = std::numeric_limits<std::uint32_t>::max();
    return b > top - a ? top : a + b;
  }

 private:
  ZeroedVector<std::uint32_t> counts_;
};

}  // namespace talus
