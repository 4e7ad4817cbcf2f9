// Reading --release (docs/architecture.md section 3): a raster (non-zero cells are sources, the value is
// a depth in metres and negative values count as depths too) or a vector layer through OGR
// (points, or polygons rasterized onto the DEM grid, with an optional `depth` attribute and,
// for rock fall, the rock-fall attributes of release_attributes.hpp), reprojected to the DEM's
// CRS.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

#include "talus/core/release.hpp"
#include "talus/gis/crs_option.hpp"
#include "talus/rockfall/rock.hpp"

namespace talus::gis {

// Where a release's depth (m) comes from (issue 17, item 7; docs/inputs.md, "Release depth"):
// the vector features' attribute `field`, the raster's values, or, with `uniform`, that depth
// on every release cell and feature whatever the file holds.
// The deepest mud-flow release (m) Talus takes: above the thickest debris-flow and shallow
// landslide releases; a deeper one is a unit error (centimetres, say) or a fill value, and a
// depth that is not a number is refused too (docs/inputs.md, "Plausible terrain").
inline constexpr double kMaxReleaseDepth = 100.0;

struct ReleaseDepthSource {
  std::string field = "depth";
  std::optional<double> uniform;  // m, > 0
};

// With `run_rock` (rock fall: the run's rock), each feature's rock-fall attributes become its
// release conditions; without it they are not read. Throws InputError naming the file when it
// is unreadable, empty, of an unsupported geometry, lies outside the DEM's valid area, or when
// a feature's attribute is out of range (naming the feature and the field).
ReleaseSet read_release(const std::filesystem::path& path, const Grid<double>& dem, const CrsOption& crs,
                        const std::optional<Rock>& run_rock = std::nullopt, const ReleaseDepthSource& depth = {});

}  // namespace talus::gis
