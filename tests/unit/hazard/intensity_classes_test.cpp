// Tests of classify_intensity (issue 17, item 3; docs/hazard-statistics.md, "Intensity
// classes"): first class that holds, all thresholds of an alternative, any alternative, products
// of layers, nodata kept, unknown layers refused.
#include "talus/hazard/intensity_classes.hpp"

#include <stdexcept>

#include <gtest/gtest.h>

namespace talus {
namespace {

GridSpec spec_of(int width) {
  GridSpec spec;
  spec.width = width;
  spec.height = 1;
  return spec;
}

IntensityThreshold above(std::vector<std::string> layers, double value, bool inclusive = false) {
  return {std::move(layers), value, inclusive};
}

// FOEN 2016 rock fall: strong > 300 kJ, medium > 30 kJ, weak > 0.
IntensityScheme rock_fall() {
  return {"test", "rock fall", "",
          {{3, "strong", "", "#d7191c", {{above({"energy"}, 300)}}},
           {2, "medium", "", "#fdae61", {{above({"energy"}, 30)}}},
           {1, "weak", "", "#ffffbf", {{above({"energy"}, 0)}}}}};
}

TEST(IntensityClasses, EachCellTakesTheFirstClassThatHoldsAndZeroWhereNone) {
  const Grid<float> energy(spec_of(7), {0.0f, 0.5f, 30.0f, 30.5f, 300.0f, 301.0f, -9999.0f});
  const Grid<float> out = classify_intensity(rock_fall(), {{"energy", &energy}});
  const std::vector<float> expected = {0, 1, 1, 2, 2, 3, -9999};  // limits belong to the weaker class
  EXPECT_EQ(out.values(), expected);
}

TEST(IntensityClasses, AnAlternativeNeedsAllItsThresholdsAndAClassAnyAlternative) {
  // Debris flow: strong where h > 1 m and v > 1 m/s, or (a second alternative) h v > 5 m2/s
  // at h >= 0.5 m; medium from 0.1 m.
  const IntensityScheme scheme{"test", "debris flow", "",
                               {{3, "strong", "", "#d7191c",
                                 {{above({"h"}, 1), above({"v"}, 1)}, {above({"h", "v"}, 5), above({"h"}, 0.5, true)}}},
                                {2, "medium", "", "#fdae61", {{above({"h"}, 0.1)}}}}};
  const Grid<float> h(spec_of(6), {2.0f, 2.0f, 0.5f, 0.4f, 0.05f, 0.2f});
  const Grid<float> v(spec_of(6), {2.0f, 0.5f, 12.0f, 20.0f, 50.0f, 1.0f});
  const Grid<float> out = classify_intensity(scheme, {{"h", &h}, {"v", &v}});
  const std::vector<float> expected = {3, 2, 3, 2, 0, 2};
  EXPECT_EQ(out.values(), expected);
}

TEST(IntensityClasses, ALayerTheRunDoesNotHaveIsRefused) {
  const Grid<float> energy(spec_of(2), 1.0f);
  EXPECT_THROW(classify_intensity(rock_fall(), {{"velocity", &energy}}), std::invalid_argument);
}

}  // namespace
}  // namespace talus
