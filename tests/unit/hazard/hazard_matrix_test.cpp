// Tests of the hazard matrix (issue 19, item 3; docs/study.md, "Hazard map"): the probability
// class of a return period with its limits inclusive, a cell's degree from its intensity class
// at that class, a reach probability lengthening the cell's return period, the highest degree
// over scenarios, nodata and unknown classes.
#include "talus/hazard/hazard_matrix.hpp"

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

// The Swiss matrix (FOEN 2016): probability high up to 30 years, medium to 100, low to 300.
HazardMatrix swiss() {
  HazardMatrix m;
  m.guideline = "test";
  m.probabilities = {"high", "medium", "low", "very low"};
  m.return_period_limits = {30, 100, 300};
  m.degrees = {{4, "high", "", "#e60000"}, {3, "medium", "", "#0070ff"}, {2, "low", "", "#ffff00"},
               {1, "residual", "", "#ffffbe"}};
  m.degree_values = {{"strong", {4, 4, 4, 1}}, {"medium", {4, 3, 3, 1}}, {"weak", {3, 2, 2, 1}}};
  return m;
}

IntensityScheme classes() {
  return {"test", "", "", {{3, "strong", "", "#000000", {}}, {2, "medium", "", "#000000", {}}, {1, "weak", "", "#000000", {}}}};
}

TEST(HazardMatrix, AReturnPeriodOnALimitBelongsToTheMoreFrequentClass) {
  const HazardMatrix m = swiss();
  EXPECT_EQ(probability_class(m, 1), 0u);
  EXPECT_EQ(probability_class(m, 30), 0u);
  EXPECT_EQ(probability_class(m, 30.5), 1u);
  EXPECT_EQ(probability_class(m, 100), 1u);
  EXPECT_EQ(probability_class(m, 300), 2u);
  EXPECT_EQ(probability_class(m, 301), 3u);
  EXPECT_EQ(probability_class(m, 1e6), 3u);
}

TEST(HazardMatrix, EachCellTakesTheDegreeOfItsIntensityAtTheReturnPeriod) {
  const Grid<float> intensity(spec_of(5), {0, 1, 2, 3, -9999});
  for (const auto& [years, expected] : std::vector<std::pair<double, std::vector<float>>>{
           {10, {0, 3, 4, 4, -9999}}, {50, {0, 2, 3, 4, -9999}}, {300, {0, 2, 3, 4, -9999}}, {1000, {0, 1, 1, 1, -9999}}}) {
    Grid<float> hazard(spec_of(5), {0, 0, 0, 0, -9999});
    raise_hazard(hazard, swiss(), classes(), intensity, years);
    EXPECT_EQ(hazard.values(), expected) << years << " years";
  }
}

TEST(HazardMatrix, ACellKeepsTheHighestDegreeOfAllScenarios) {
  Grid<float> hazard(spec_of(3), {0, 0, 0});
  // A frequent weak event and a rare strong one: blue from the first, red from the second.
  raise_hazard(hazard, swiss(), classes(), Grid<float>(spec_of(3), {1, 1, 0}), 10);
  raise_hazard(hazard, swiss(), classes(), Grid<float>(spec_of(3), {0, 3, 1}), 200);
  EXPECT_EQ(hazard.values(), (std::vector<float>{3, 4, 2}));
}

TEST(HazardMatrix, AReachProbabilityLengthensTheCellsReturnPeriod) {
  // Strong intensity from a 10-year scenario: reached by every block (10 years: high), by one in
  // five (50 years: still high for strong), by one in 50 (500 years: residual), by none (0).
  const Grid<float> intensity(spec_of(4), {3, 3, 3, 3});
  const Grid<float> reach(spec_of(4), {1.0f, 0.2f, 0.02f, 0.0f});
  Grid<float> hazard(spec_of(4), {0, 0, 0, 0});
  raise_hazard(hazard, swiss(), classes(), intensity, 10, &reach);
  EXPECT_EQ(hazard.values(), (std::vector<float>{4, 4, 1, 0}));
  // Medium intensity: 10 years high, 50 years medium, 500 years residual.
  Grid<float> medium(spec_of(4), {0, 0, 0, 0});
  raise_hazard(medium, swiss(), classes(), Grid<float>(spec_of(4), {2, 2, 2, 2}), 10, &reach);
  EXPECT_EQ(medium.values(), (std::vector<float>{4, 3, 1, 0}));
}

TEST(HazardMatrix, AnIntensityClassWithoutARowIsRefused) {
  IntensityScheme other = classes();
  other.classes.push_back({4, "extreme", "", "#000000", {}});
  Grid<float> hazard(spec_of(1), {0});
  EXPECT_THROW(raise_hazard(hazard, swiss(), other, Grid<float>(spec_of(1), {1}), 10), std::invalid_argument);
}

}  // namespace
}  // namespace talus
