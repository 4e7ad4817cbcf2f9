// CellQuantiles: lazily created per-cell logarithmic histograms and their exact merge
// (docs/architecture.md section 2, "Statistical maps").
#include "talus/hazard/cell_quantiles.hpp"

#include <limits>
#include <stdexcept>
#include <utility>

namespace talus {

CellQuantiles::CellQuantiles(std::size_t cell_count, LogBinning binning)
    : binning_(std::move(binning)), slot_(cell_count) {   // every slot starts at no_histogram (0)
  if (cell_count >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("CellQuantiles: too many cells for 32-bit cell indices");
  }
}

LogHistogram& CellQuantiles::new_histogram(std::size_t cell) {
  histograms_.emplace_back();
  cells_.push_back(static_cast<std::uint32_t>(cell));
  slot_[cell] = static_cast<std::uint32_t>(histograms_.size());
  return histograms_.back();
}

void CellQuantiles::merge(const CellQuantiles& other) {
  if (other.size() != size() || !(other.binning_ == binning_)) {
    throw std::invalid_argument("CellQuantiles::merge: different cell counts or binnings");
  }
  const std::size_t reached = other.histograms_.size();   // fixed first: merging into itself
  for (std::size_t i = 0; i < reached; ++i) {
    const std::size_t cell = other.cells_[i];
    if (slot_[cell] == no_histogram) {
      histograms_.push_back(other.histograms_[i]);
      cells_.push_back(other.cells_[i]);
      slot_[cell] = static_cast<std::uint32_t>(histograms_.size());
    } else {
      histograms_[slot_[cell] - 1].merge(other.histograms_[i]);
    }
  }
}

double CellQuantiles::quantile(std::size_t cell, double q) const {
  const std::uint32_t slot = slot_[cell];
  return slot == no_histogram ? 0.0 : histograms_[slot - 1].quantile(q, binning_);
}

std::uint64_t CellQuantiles::count(std::size_t cell) const {
  const std::uint32_t slot = slot_[cell];
  return slot == no_histogram ? 0 : histograms_[slot - 1].count();
}

std::size_t CellQuantiles::memory_bytes() const {
  std::size_t bytes = sizeof(*this) + slot_.capacity() * sizeof(std::uint32_t) +
                      cells_.capacity() * sizeof(std::uint32_t) +
                      (histograms_.capacity() - histograms_.size()) * sizeof(LogHistogram);
  for (const LogHistogram& h : histograms_) bytes += h.memory_bytes();
  return bytes;
}

void CellQuantiles::write(ByteWriter& out) const {
  out.put<std::uint64_t>(size());
  out.put<std::uint64_t>(histograms_.size());
  for (std::size_t i = 0; i < histograms_.size(); ++i) {
    out.put(cells_[i]);
    histograms_[i].write(out);
  }
}

void CellQuantiles::read(ByteReader& in) {
  if (in.get_cell_count() != size() || !histograms_.empty()) {
    throw std::runtime_error("rank message: quantiles of another grid");
  }
  const std::uint64_t reached = in.get<std::uint64_t>();
  for (std::uint64_t i = 0; i < reached; ++i) {
    const auto cell = in.get_cell<std::uint32_t>();
    if (cell >= size() || slot_[cell] != no_histogram) throw std::runtime_error("rank message: a cell outside the grid");
    new_histogram(cell).read(in);
  }
}

}  // namespace talus
