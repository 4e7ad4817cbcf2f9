// particles.gpkg (issue 5, "optional particle snapshots in a GeoPackage with a time attribute,
// for the QGIS temporal controller"): the mud-flow particles at regular times as 3D points, one
// feature per particle and snapshot, with the snapshot's time span as date-times QGIS animates,
// and particles.qml beside it (points coloured by flow depth, temporal settings).
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "talus/gis/layer_writer.hpp"
#include "talus/mudflow/mudflow_simulation.hpp"

namespace talus::gis {

// The clock of the animation: simulated time t (s) after release is the date-time
// 2000-01-01T00:00:00Z + t, so QGIS's temporal controller reads elapsed time as hh:mm:ss.
inline constexpr const char* kSnapshotEpoch = "2000-01-01T00:00:00Z";

// Writes a GeoPackage at `path` (replacing a file there) with one layer "particles" of Point Z
// features (x, y in the CRS of `crs_wkt`, z the ground elevation under the particle, m; when
// crs_wkt is empty, the GeoPackage's "Undefined Cartesian SRS" for local metric coordinates),
// all in one transaction. Each feature holds its snapshot's time_s (s), the span in which QGIS
// shows it, start_time = epoch + time_s to end_time = 1 ms before the next snapshot's
// start_time (the last snapshot: 1 ms before one `interval` later; to the millisecond, UTC), and
// the particle's depth_m, speed_m_s, mass_kg and radius_m. Snapshots come in time order;
// interval: s between snapshots (> 0.001).
// Throws std::runtime_error naming the path and removes what it wrote.
void write_particle_snapshots(const std::filesystem::path& path, const std::vector<ParticleSnapshot>& snapshots,
                              double interval, const std::string& crs_wkt);

// The QML style of particles.gpkg: points coloured by depth_m with the flow_depth_max classes,
// field aliases with units, and temporal settings (start_time to end_time) for QGIS 3.22.
std::string particle_style();

// Adds particles.gpkg and particles.qml to a layer set (committed with it).
void add_particle_snapshots(LayerWriter& writer, const std::vector<ParticleSnapshot>& snapshots, double interval,
                            const std::string& crs_wkt);

}  // namespace talus::gis
