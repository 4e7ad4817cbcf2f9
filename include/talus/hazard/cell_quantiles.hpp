// CellQuantiles: a LogHistogram per grid cell, created only for cells that receive a value
// (docs/architecture.md section 2, "Statistical maps": 95th percentiles of kinetic energy and jump height
// over the passages through a cell). Memory: 4 bytes per cell for the index, plus, per reached
// cell, one histogram whose window never exceeds the binning's bins. Merging is exact (integer
// bin counts), so quantiles after any sequence of merges equal those of a single accumulation.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "talus/hazard/log_binning.hpp"
#include "talus/hazard/log_histogram.hpp"
#include "talus/hazard/zeroed_vector.hpp"

namespace talus {

class CellQuantiles {
 public:
  CellQuantiles(std::size_t cell_count, LogBinning binning);

  void add(std::size_t cell, double value) { histogram(cell).add(value, binning_); }
  // Adds every cell's histogram of `other` (same cell count and binning) into this one.
  void merge(const CellQuantiles& other);
  // For MPI ranks (core/byte_stream.hpp): the reached cells' histograms; read() into an empty
  // one of the same size and binning.
  void write(ByteWriter& out) const;
  void read(ByteReader& in);

  // The q-quantile of the values added to the cell; 0 for a cell without values.
  double quantile(std::size_t cell, double q) const;
  std::uint64_t count(std::size_t cell) const;
  std::size_t reached_cells() const { return histograms_.size(); }
  std::size_t size() const { return slot_.size(); }
  const LogBinning& binning() const { return binning_; }
  std::size_t memory_bytes() const;

 private:
  static constexpr std::uint32_t no_histogram = 0;
  LogHistogram& histogram(std::size_t cell) {
    const std::uint32_t slot = slot_[cell];
    return slot != no_histogram ? histograms_[slot - 1] : new_histogram(cell);
  }
  LogHistogram& new_histogram(std::size_t cell);

  LogBinning binning_;
  ZeroedVector<std::uint32_t> slot_;       // per cell: no_histogram, or 1 + index in histograms_
  std::vector<LogHistogram> histograms_;    // reached cells, in the order they were reached
  std::vector<std::uint32_t> cells_;        // the cell of each histogram
};

}  // namespace talus
