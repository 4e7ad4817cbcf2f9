// Rock-fall sources found from the terrain (issue 19, item 1; docs/study.md, "Sources from the
// slope"): the method of Loye, Jaboyedoff and Pedrazzini (2009), Identification of potential
// rockfall source areas at a regional scale using a DEM-based geomorphometric analysis, Nat.
// Hazards Earth Syst. Sci. 9:1643-1653. The distribution of the DEM's slope angles is decomposed
// into Gaussian distributions, one per morphological unit (plains, footslopes, steep slopes, rock
// cliffs); cells steeper than the angle where the rock-cliff Gaussian becomes dominant over the
// steep-slope one are potential sources. The threshold follows from the DEM itself, so it adapts
// to its resolution (coarser DEMs smooth cliffs to lower angles), as the paper shows over six
// resolutions.
#pragma once

#include <array>
#include <optional>
#include <set>

#include "talus/core/grid.hpp"

namespace talus {

// Slope angle (degrees) of every cell by Horn's 3 x 3 method (as `gdaldem slope`); nodata (the
// grid's) at the edge and next to invalid cells.
Grid<float> slope_angles(const Grid<double>& elevation);

// One unit of the decomposition: share of the cells, mean and standard deviation (degrees).
struct SlopeUnit {
  double weight = 0, mean = 0, sd = 0;
};

// The four units, fitted to the slope angles' histogram (0.5 degree bins) by expectation-
// maximisation from fixed starting units (means 5, 20, 35 and 55 degrees), so the same DEM always
// gives the same fit; sorted by mean.
std::array<SlopeUnit, 4> slope_units(const Grid<float>& slopes);

// The smallest angle (degrees, to 0.1) above the steep-slope unit's mean where the rock-cliff
// unit's weighted density exceeds the steep-slope unit's; none when it never does below 90.
std::optional<double> cliff_threshold(const std::array<SlopeUnit, 4>& units);

// 1 where the slope is at least `threshold_deg` and, unless `classes` is empty, the cell's
// lithology class is among them; 0 elsewhere, also where the slope is nodata (a release raster
// reads every non-zero cell as a source).
Grid<float> source_mask(const Grid<float>& slopes, double threshold_deg, const Grid<int>& lithology,
                        const std::set<int>& classes);

}  // namespace talus
