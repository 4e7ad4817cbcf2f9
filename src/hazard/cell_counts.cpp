// CellCounts: merge of per-cell counts (docs/architecture.md section 2, "Statistical maps").
#include "talus/hazard/cell_counts.hpp"

#include <stdexcept>

namespace talus {

void CellCounts::merge(const CellCounts& other) {
  if (other.size() != size()) throw std::invalid_argument("CellCounts::merge: different cell counts");
  // Cells without counts in `other` are only read: untouched zero pages stay untouched.
  for (std::size_t i = 0; i < counts_.size(); ++i) {
    if (other.counts_[i] != 0) counts_[i] = saturating_sum(counts_[i], other.counts_[i]);
  }
}

}  // namespace talus
