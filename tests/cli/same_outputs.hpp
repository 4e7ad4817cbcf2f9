// Comparing two runs' outputs (issue 19): byte-identical rasters and the same trajectory lines,
// for the tests that split a run among MPI ranks or tiles.
#pragma once

#include <gtest/gtest.h>

#include <ogrsf_frmts.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace talus::test {

inline std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

// Every .tif under `a` has a byte-identical twin under `b`; returns how many were compared.
inline int expect_same_rasters(const std::filesystem::path& a, const std::filesystem::path& b) {
  int compared = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(a)) {
    if (entry.path().extension() != ".tif") continue;
    const std::filesystem::path twin = b / std::filesystem::relative(entry.path(), a);
    EXPECT_TRUE(std::filesystem::exists(twin)) << twin;
    EXPECT_TRUE(file_bytes(entry.path()) == file_bytes(twin)) << entry.path() << " differs from " << twin;
    ++compared;
  }
  return compared;
}

// Every trajectory of a run's trajectories.gpkg: its ids and its line as WKT.
inline std::vector<std::string> trajectory_lines(const std::filesystem::path& out) {
  GDALAllRegister();
  GDALDatasetUniquePtr data(GDALDataset::Open((out / "trajectories.gpkg").c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  std::vector<std::string> lines;
  if (!data) return lines;
  for (auto& feature : *data->GetLayerByName("trajectories")) {
    char* wkt = nullptr;
    feature->GetGeometryRef()->exportToWkt(&wkt);
    lines.push_back(std::to_string(feature->GetFieldAsInteger64("source_id")) + "/" +
                    std::to_string(feature->GetFieldAsInteger64("run_id")) + " " + wkt);
    CPLFree(wkt);
  }
  return lines;
}

}  // namespace talus::test
