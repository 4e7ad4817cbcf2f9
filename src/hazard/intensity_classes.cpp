// Intensity classes from a run's layers (intensity_classes.hpp; docs/hazard-statistics.md,
// "Intensity classes").
#include "talus/hazard/intensity_classes.hpp"

#include <stdexcept>

namespace talus {
namespace {

// A threshold with its layers looked up.
struct BoundThreshold {
  std::vector<const Grid<float>*> grids;
  double above = 0.0;
  bool inclusive = false;

  bool holds(std::size_t cell) const {
    double product = 1.0;
    for (const Grid<float>* grid : grids) product *= static_cast<double>((*grid)[cell]);
    return inclusive ? product >= above : product > above;
  }
};

struct BoundClass {
  float value = 0.0f;
  std::vector<std::vector<BoundThreshold>> when;

  bool holds(std::size_t cell) const {
    for (const auto& alternative : when) {
      bool all = true;
      for (const BoundThreshold& threshold : alternative) all = all && threshold.holds(cell);
      if (all) return true;
    }
    return false;
  }
};

}  // namespace

Grid<float> classify_intensity(const IntensityScheme& scheme, const std::map<std::string, const Grid<float>*>& layers) {
  const Grid<float>* first = nullptr;
  std::vector<BoundClass> classes;
  for (const IntensityClass& c : scheme.classes) {
    BoundClass& bound = classes.emplace_back();
    bound.value = static_cast<float>(c.value);
    for (const auto& alternative : c.when) {
      auto& thresholds = bound.when.emplace_back();
      for (const IntensityThreshold& threshold : alternative) {
        BoundThreshold& t = thresholds.emplace_back();
        t.above = threshold.above;
        t.inclusive = threshold.inclusive;
        for (const std::string& name : threshold.layers) {
          const auto found = layers.find(name);
          if (found == layers.end() || found->second == nullptr) {
            throw std::invalid_argument("intensity class '" + c.name + "' of " + scheme.guideline + " uses the layer '" +
                                        name + "', which this process does not write");
          }
          if (first == nullptr) first = found->second;
          require_same_grid(first->spec(), found->second->spec(), "intensity layer " + name);
          t.grids.push_back(found->second);
        }
      }
    }
  }
  if (first == nullptr) throw std::invalid_argument("the intensity guideline " + scheme.guideline + " has no threshold");

  Grid<float> out(first->spec(), 0.0f);
  for (std::size_t cell = 0; cell < out.size(); ++cell) {
    if (!first->is_valid(cell)) {
      out[cell] = static_cast<float>(out.spec().nodata);
      continue;
    }
    for (const BoundClass& c : classes) {
      if (c.holds(cell)) {
        out[cell] = c.value;
        break;
      }
    }
  }
  return out;
}

}  // namespace talus
