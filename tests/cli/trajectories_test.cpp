// trajectories.gpkg of a real run for analysis (issue 17, item 6): lines whose ids join to the
// release layer, time as M, no zero-length segment; a vertex layer with time, distance, speed,
// energy and jump height; the documented profile plot (scripts/trajectory_profile.py) from it.
#include <gdal_priv.h>
#include <gtest/gtest.h>
#include <ogrsf_frmts.h>

#include <cstdlib>
#include <map>
#include <memory>
#include <set>
#include <utility>

#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

GDALDatasetUniquePtr open_vector(const fs::path& path) {
  GDALAllRegister();
  return GDALDatasetUniquePtr(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
}

TEST(RockfallTrajectories, JoinToTheReleaseCarryTimeAndHoldTheVerticesOfAProfile) {
  const auto root = test::fresh_folder("rockfall_trajectories");
  const auto sample = test::source_dir() / "sample_dem";
  const auto out = root / "out";
  const auto result = test::run_talus({"rockfall", "--dem", (sample / "dem.tif").string(), "--release",
                                       (sample / "rockfall_release.gpkg").string(), "--out", out.string(), "--runs", "2"},
                                      root);
  ASSERT_EQ(result.exit_code, 0) << result.err;

  std::set<GIntBig> release_fids;
  const auto release = open_vector(sample / "rockfall_release.gpkg");
  ASSERT_TRUE(release);
  for (auto& feature : *release->GetLayer(0)) release_fids.insert(feature->GetFID());

  const auto data = open_vector(out / "trajectories.gpkg");
  ASSERT_TRUE(data);
  OGRLayer* lines = data->GetLayerByName("trajectories");
  OGRLayer* vertices = data->GetLayerByName("trajectory_vertices");
  ASSERT_NE(lines, nullptr);
  ASSERT_NE(vertices, nullptr);
  EXPECT_TRUE(OGR_GT_HasM(lines->GetGeomType()));

  std::map<std::pair<GIntBig, GIntBig>, int> points_of_line;  // (source, run) -> vertices
  int checked = 0;
  for (auto& feature : *lines) {
    EXPECT_TRUE(release_fids.count(feature->GetFieldAsInteger64("release_fid")))
        << "release_fid " << feature->GetFieldAsInteger64("release_fid") << " is no feature of the release";
    const OGRGeometry* geometry = feature->GetGeometryRef();
    if (geometry == nullptr) continue;
    const auto* line = geometry->toLineString();
    points_of_line[{feature->GetFieldAsInteger64("source_id"), feature->GetFieldAsInteger64("run_id")}] =
        line->getNumPoints();
    EXPECT_EQ(line->getM(0), 0.0);
    for (int i = 1; i < line->getNumPoints(); ++i) {
      const double dx = line->getX(i) - line->getX(i - 1), dy = line->getY(i) - line->getY(i - 1),
                   dz = line->getZ(i) - line->getZ(i - 1);
      ASSERT_GE(dx * dx + dy * dy + dz * dz, 1e-12) << "zero-length segment at vertex " << i;
      ASSERT_GT(line->getM(i), line->getM(i - 1)) << "time does not grow at vertex " << i;
    }
    ++checked;
  }
  EXPECT_GT(checked, 100);

  std::map<std::pair<GIntBig, GIntBig>, int> vertex_count;
  for (auto& feature : *vertices) {
    ++vertex_count[{feature->GetFieldAsInteger64("source_id"), feature->GetFieldAsInteger64("run_id")}];
    EXPECT_GE(feature->GetFieldAsDouble("speed_m_s"), 0.0);
    EXPECT_GE(feature->GetFieldAsDouble("energy_kj"), 0.0);
    EXPECT_GE(feature->GetFieldAsDouble("distance_m"), 0.0);
  }
  for (const auto& [key, count] : points_of_line) EXPECT_EQ(vertex_count[key], count);

  const auto png = root / "profile.png";
  const std::string command = "/usr/bin/python3 '" + (test::source_dir() / "scripts/trajectory_profile.py").string() +
                              "' '" + out.string() + "' --source 0 --run 0 --dem '" + (sample / "dem.tif").string() +
                              "' --png '" + png.string() + "' > /dev/null";
  ASSERT_EQ(std::system(command.c_str()), 0);
  ASSERT_TRUE(fs::exists(png));
  EXPECT_GT(fs::file_size(png), 20000u);  // three panels of curves, not an empty figure
}

}  // namespace
}  // namespace talus
