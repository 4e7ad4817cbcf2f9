// Hazard degrees from intensity and probability (hazard_matrix.hpp; docs/study.md, "Hazard map").
#include "talus/hazard/hazard_matrix.hpp"

#include <algorithm>
#include <stdexcept>

namespace talus {

std::size_t probability_class(const HazardMatrix& matrix, double return_period_years) {
  std::size_t k = 0;
  while (k < matrix.return_period_limits.size() && return_period_years > matrix.return_period_limits[k]) ++k;
  return k;
}

void raise_hazard(Grid<float>& hazard, const HazardMatrix& matrix, const IntensityScheme& scheme,
                  const Grid<float>& intensity, double return_period_years, const Grid<float>* reach) {
  require_same_grid(hazard.spec(), intensity.spec(), "hazard map and intensity layer");
  if (reach != nullptr) require_same_grid(hazard.spec(), reach->spec(), "hazard map and reach probability");
  // Per intensity class value, its row of degrees.
  std::map<int, const std::vector<int>*> row_of;
  for (const IntensityClass& c : scheme.classes) {
    const auto row = matrix.degree_values.find(c.name);
    if (row == matrix.degree_values.end()) {
      throw std::invalid_argument("hazard matrix of " + matrix.guideline + ": no row for the intensity class '" +
                                  c.name + "' of " + scheme.guideline);
    }
    row_of[c.value] = &row->second;
  }
  const std::size_t scenario_column = probability_class(matrix, return_period_years);
  for (std::size_t cell = 0; cell < hazard.size(); ++cell) {
    if (!intensity.is_valid(cell) || !hazard.is_valid(cell)) continue;
    const auto row = row_of.find(static_cast<int>(intensity[cell]));
    if (row == row_of.end()) continue;
    std::size_t column = scenario_column;
    if (reach != nullptr) {
      const double probability = (*reach)[cell];
      if (!(probability > 0.0)) continue;  // not reached: no hazard from this scenario
      column = probability_class(matrix, return_period_years / std::min(probability, 1.0));
    }
    hazard[cell] = std::max(hazard[cell], static_cast<float>(row->second->at(column)));
  }
}

}  // namespace talus
