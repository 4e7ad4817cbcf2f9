// The rock-fall conditions of a release raster's cells (issue 16; docs/inputs.md, "Rock-fall
// attributes"): bands after the first whose description names an attribute (`shape` as a code
// 1 sphere, 2 ellipsoid, 3 box; `block_size` as one diameter; `density` or `mass`; `vx`, `vy`,
// `vz`; `release_height`) give each release cell its own block, start velocity and height, read
// and checked as a feature's attributes are (release_attributes.hpp).
#pragma once

#include <filesystem>

#include "talus/core/release.hpp"
#include "talus/gis/crs_option.hpp"
#include "talus/rockfall/rock.hpp"

namespace talus::gis {

// Adds to `release` (its cells read from band 1 of `path`) the conditions the attribute bands
// give each release cell, aligned onto the DEM's grid by the nearest cell; a band's nodata keeps
// the run's value. A band after the first without an attribute's name, or a bad value, is an
// InputError naming the file, the band or the cell, and the problem.
void add_raster_conditions(const std::filesystem::path& path, const GridSpec& dem, const CrsOption& crs,
                           const Rock& run_rock, ReleaseSet& release);

}  // namespace talus::gis
