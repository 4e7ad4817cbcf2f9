// Intensity classes of a hazard guideline (issue 17, item 3; docs/hazard-statistics.md,
// "Intensity classes"): each class holds where any of its alternatives holds, an alternative
// being a set of thresholds on a run's layers that must all be exceeded, e.g. FOEN 2016's strong
// rock-fall intensity "energy_p95 > 300" (kJ) or a debris flow's "flow_depth_max > 1 and
// velocity_max > 1". The classes are data (src/cli/intensity_guidelines.toml), not code.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "talus/core/grid.hpp"

namespace talus {

// The product of the named layers' values (one layer: its value) compared with a threshold in
// the product's unit: value > above, or >= when inclusive.
struct IntensityThreshold {
  std::vector<std::string> layers;
  double above = 0.0;
  bool inclusive = false;
};

struct IntensityClass {
  int value = 0;               // the class's cell value in the intensity layer, 1 and up
  std::string name;            // e.g. "strong"
  std::string label;           // the legend's text, e.g. "strong: E > 300 kJ"
  std::string colour;          // #rrggbb
  std::vector<std::vector<IntensityThreshold>> when;  // any alternative, all of its thresholds
};

// One guideline's classes for one process, strongest first: a cell takes the first class that
// holds, 0 where none does.
struct IntensityScheme {
  std::string guideline;   // e.g. "foen-2016"
  std::string title;       // e.g. "Swiss federal intensity classes (FOEN 2016)"
  std::string source;      // the publication the thresholds come from
  std::vector<IntensityClass> classes;
};

// The intensity class of every cell from the run's layers by name (all on one grid); cells
// invalid in the first layer named by the scheme are the grid's nodata. Throws
// std::invalid_argument naming a layer the scheme uses and `layers` lacks.
Grid<float> classify_intensity(const IntensityScheme& scheme, const std::map<std::string, const Grid<float>*>& layers);

}  // namespace talus
