// CellMaxima: merge of per-cell maxima (docs/architecture.md section 2, "Statistical maps").
#include "talus/hazard/cell_maxima.hpp"

#include <stdexcept>

namespace talus {

void CellMaxima::merge(const CellMaxima& other) {
  if (other.size() != size()) throw std::invalid_argument("CellMaxima::merge: different cell counts");
  // Written only where `other` is larger: untouched zero pages stay untouched.
  for (std::size_t i = 0; i < maxima_.size(); ++i) {
    if (other.maxima_[i] > maxima_[i]) maxima_[i] = other.maxima_[i];
  }
}

}  // namespace talus
