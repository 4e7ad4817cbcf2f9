// trajectories.gpkg (docs/architecture.md section 3; issue 17, item 6): the sampled rock-fall trajectories
// as 3D lines with the time since release as M, one feature per trajectory with its run, source,
// release feature, stop reason, maximum energy and runout length; a second layer
// "trajectory_vertices" with each vertex's time, distance along the path, speed, energy and jump
// height for profile plots; the QML style (gis/styles/trajectories.qml) beside it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "talus/gis/layer_writer.hpp"
#include "talus/rockfall/trajectory_line.hpp"

namespace talus::gis {

// Writes a GeoPackage at `path` (replacing a file there) with the layer "trajectories" of
// LineStringZM features and the layer "trajectory_vertices" of Point Z features in the CRS of `crs_wkt` (when empty, the GeoPackage's "Undefined
// Cartesian SRS" for local metric coordinates), all in one transaction. A
// line with fewer than two points is a feature without geometry (its attributes still count).
// Throws std::runtime_error naming the path and removes what it wrote.
void write_trajectories(const std::filesystem::path& path, const std::vector<TrajectoryLine>& lines,
                        const std::string& crs_wkt);

// Adds trajectories.gpkg and its style trajectories.qml to a layer set (committed with it).
void add_trajectories(LayerWriter& writer, const std::vector<TrajectoryLine>& lines, const std::string& crs_wkt);

}  // namespace talus::gis
