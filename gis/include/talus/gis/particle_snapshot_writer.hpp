// particles.gpkg (issue 5, "optional particle snapshots in a GeoPackage with a time attribute,
// for the QGIS temporal controller"): the mud-flow particles at regular times as 3D points, one
// feature per particle and snapshot, with the snapshot's time span as date-times QGIS animates,
// particles.qml beside it (points coloured by flow depth, temporal settings) and particles.qlr,
// the layer definition that opens in QGIS with its animation on (issue 17, item 6).
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "talus/gis/layer_writer.hpp"
#include "talus/mudflow/mudflow_simulation.hpp"

namespace talus::gis {

// The clock of the animation: simulated time t (s) after release is the date-time start + t
// (`--start-time`, [outputs] snapshot_start), written without a time zone: QGIS 3.22 filters a
// GeoPackage's date-times by comparing their text with its own, which has no zone, so a stored
// "Z" hid every snapshot at its own instant. By default the release is at 2000-01-01T00:00:00,
// so the clock reads the time since release; the run's own time would make two runs of the same
// inputs differ.
inline constexpr const char* kDefaultSnapshotStart = "2000-01-01T00:00:00";

// Seconds after 1970-01-01T00:00:00 of "YYYY-MM-DDTHH:MM:SS" (a final "Z" is allowed), years
// 1000-9999; nothing when the text is not such a date-time.
std::optional<std::int64_t> parse_snapshot_start(const std::string& text);

// Writes a GeoPackage at `path` (replacing a file there) with one layer "particles" of Point Z
// features (x, y in the CRS of `crs_wkt`, z the ground elevation under the particle, m; when
// crs_wkt is empty, the GeoPackage's "Undefined Cartesian SRS" for local metric coordinates),
// all in one transaction, without a spatial index (a smaller file; QGIS draws it filtered by
// time). Each feature holds its snapshot's time_s (s), the span in which QGIS shows it,
// start_time = start + time_s to end_time = 1 ms before the next snapshot's start_time (the
// last snapshot: 1 ms before one `interval` later; to the millisecond, no time zone), and the
// particle's depth_m, speed_m_s, mass_kg and radius_m. Snapshots come in time order; interval:
// s between snapshots (> 0.001); start: the release's date-time, s after 1970-01-01.
// Throws std::runtime_error naming the path and removes what it wrote.
void write_particle_snapshots(const std::filesystem::path& path, const std::vector<ParticleSnapshot>& snapshots,
                              double interval, const std::string& crs_wkt, std::int64_t start);

// The QML style of particles.gpkg: points coloured by depth_m with the flow_depth_max classes,
// field aliases with units, and temporal settings (start_time to end_time) for QGIS 3.22.
std::string particle_style();

// particles.qlr: a QGIS layer definition of ./particles.gpkg in `crs_wkt` with the style of
// particle_style(), temporal settings included, which QGIS 3.22 applies when the file is
// dragged in or added (Layer > Add from Layer Definition File); opened directly, the GeoPackage
// comes up with its animation off.
std::string particle_layer_definition(const std::string& crs_wkt);

// Adds particles.gpkg, particles.qml and particles.qlr to a layer set (committed with it).
void add_particle_snapshots(LayerWriter& writer, const std::vector<ParticleSnapshot>& snapshots, double interval,
                            const std::string& crs_wkt, std::int64_t start);

}  // namespace talus::gis
