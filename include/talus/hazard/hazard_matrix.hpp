// Hazard degrees from intensity and probability (issue 19, item 3; docs/study.md, "Hazard
// map"): a guideline's matrix gives each intensity class, at each probability class of a
// scenario's return period, a hazard degree (FOEN 2016: high, medium, low, residual). The matrix
// is data (src/cli/intensity_guidelines.toml), not code.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "talus/core/grid.hpp"
#include "talus/hazard/intensity_classes.hpp"

namespace talus {

struct HazardDegree {
  int value = 0;       // the degree's cell value in the hazard map, 1 and up; higher is more hazardous
  std::string name;    // e.g. "high"
  std::string label;   // the legend's text
  std::string colour;  // #rrggbb
};

struct HazardMatrix {
  std::string guideline;  // e.g. "foen-2016"
  std::string source;     // the publication the matrix comes from
  // Probability classes, most frequent first, and the longest return period (years) of each but
  // the last: a scenario of return period T takes the first class k with T <= limits[k], the last
  // class above every limit.
  std::vector<std::string> probabilities;
  std::vector<double> return_period_limits;
  std::vector<HazardDegree> degrees;  // strongest first
  // Per intensity class name, the degree value at each probability class (0: no hazard).
  std::map<std::string, std::vector<int>> degree_values;
};

// The probability class (an index into matrix.probabilities) of a return period in years.
std::size_t probability_class(const HazardMatrix& matrix, double return_period_years);

// Raises every cell of `hazard` to the degree the matrix gives the cell's intensity class (a
// value of `scheme` in `intensity`) at the cell's return period: a cell's hazard is the highest
// degree of all the scenarios added. The cell's return period is the scenario's, or with `reach`
// (a probability per cell, 0-1) the scenario's divided by the cell's: an event reaches the cell
// once in that many of its occurrences (the onset and reach probabilities of Swiss rock-fall
// practice, docs/study.md). Cells invalid in `intensity` stay as they are; the grids must match.
// Throws std::invalid_argument for an intensity class the matrix does not list.
void raise_hazard(Grid<float>& hazard, const HazardMatrix& matrix, const IntensityScheme& scheme,
                  const Grid<float>& intensity, double return_period_years, const Grid<float>* reach = nullptr);

}  // namespace talus
