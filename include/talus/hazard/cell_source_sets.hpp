// CellSourceSets: per grid cell, the set of release sources whose rocks passed it, the
// denominator of the reach probability per contributing source and Rockyfor3D's
// `Nr_sourcecells` (docs/hazard-statistics.md, "How `source_count` is gathered"). A set is
// stored as sorted, disjoint, non-adjacent intervals of source numbers: release cells are
// numbered row by row, so the sources that reach one cell mostly come in runs of neighbours
// and a set takes a few intervals.
// Merging is a set union, exact and independent of the merge order, so the counts of statistics
// merged across threads equal those of a single accumulation even when the runs of one source
// were split between threads. Memory: 4 bytes per cell for the index, plus, per reached cell,
// one vector of 8-byte intervals.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "talus/core/byte_stream.hpp"
#include "talus/hazard/zeroed_vector.hpp"

namespace talus {

// Sources first..last, both included.
struct SourceInterval {
  std::uint32_t first = 0;
  std::uint32_t last = 0;
  friend bool operator==(const SourceInterval&, const SourceInterval&) = default;
};

class CellSourceSets {
 public:
  explicit CellSourceSets(std::size_t cell_count);

  // Puts `source` into the cell's set. Sources added in rising order (as one thread's runs
  // come) extend or append the last interval; any other order is inserted in place.
  void add(std::size_t cell, std::uint32_t source);
  // Unites every cell's set of `other` (same cell count) with this one's.
  void merge(const CellSourceSets& other);
  // For MPI ranks (core/byte_stream.hpp): the reached cells' sets; read() into an empty one of
  // the same size.
  void write(ByteWriter& out) const;
  void read(ByteReader& in);

  // Number of distinct sources in the cell's set; 0 for a cell no source reached.
  std::uint64_t count(std::size_t cell) const;
  std::span<const SourceInterval> intervals(std::size_t cell) const;
  std::size_t reached_cells() const { return sets_.size(); }
  std::size_t size() const { return slot_.size(); }

 private:
  static constexpr std::uint32_t no_set = 0;
  std::vector<SourceInterval>& set(std::size_t cell);

  ZeroedVector<std::uint32_t> slot_;                 // per cell: no_set, or 1 + index in sets_
  std::vector<std::vector<SourceInterval>> sets_;    // reached cells, in the order they were reached
  std::vector<std::uint32_t> cells_;                 // the cell of each set
};

}  // namespace talus
