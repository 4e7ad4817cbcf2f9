// A layer Talus wrote, read back (issue 19: `talus study` combines its scenarios' layers): band 1
// as Float32 on the file's own grid, with its CRS and nodata.
#pragma once

#include <filesystem>

#include "talus/core/grid.hpp"

namespace talus::gis {

// Throws InputError naming the file when it is missing or not a raster.
Grid<float> read_layer(const std::filesystem::path& path);

}  // namespace talus::gis
