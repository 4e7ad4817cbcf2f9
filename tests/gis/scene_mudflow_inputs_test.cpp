// The scene's mud-flow inputs (issue 5): the erodible-depth raster aligned onto the DEM grid,
// and vector releases that must give each feature its release depth.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "raster_fixtures.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/scene.hpp"
#include "test_paths.hpp"

namespace talus::gis {
namespace {

using test::RasterFixture;

// The DEM of every test: 40 x 30 cells of 10 m from (500000, 5200000), EPSG:32632.
SceneInputs inputs_in(const std::filesystem::path& folder) {
  write_raster(folder / "dem.tif", RasterFixture{});
  SceneInputs inputs;
  inputs.dem = folder / "dem.tif";
  return inputs;
}

// The message of the InputError that loading the scene throws, or "" when it loads.
std::string load_error(const SceneInputs& inputs) {
  try {
    load_scene(inputs);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneErodible, NoRasterMeansNoErodibleGrid) {
  const auto folder = test::fresh_folder("erodible_none");
  EXPECT_FALSE(load_scene(inputs_in(folder)).erodible.has_value());
}

TEST(SceneErodible, NegativeAndNodataCellsHoldNoMaterial) {
  const auto folder = test::fresh_folder("erodible_same_grid");
  SceneInputs inputs = inputs_in(folder);
  RasterFixture erodible;
  erodible.value = [](int c, int r) { return c < 10 ? -0.5 : c < 20 ? -9999.0 : 0.25 * (r % 3); };
  write_raster(folder / "erodible.tif", erodible);
  inputs.erodible = folder / "erodible.tif";
  const Scene scene = load_scene(inputs);
  ASSERT_TRUE(scene.erodible.has_value());
  EXPECT_TRUE(scene.erodible->spec().same_grid(scene.dem.elevation.spec()));
  for (int r = 0; r < 30; ++r) {
    for (int c = 0; c < 40; ++c) {
      // Same grid, no resampling: the file's Float32 values exactly.
      const float expected = c < 20 ? 0.0f : static_cast<float>(0.25 * (r % 3));
      ASSERT_EQ(scene.erodible->at(c, r), expected) << "cell " << c << ", " << r;
    }
  }
  bool named_negative = false;
  for (const auto& problem : scene.problems) named_negative |= problem.find("300 cells hold negative depths") != std::string::npos;
  EXPECT_TRUE(named_negative);
}

TEST(SceneErodible, AlignsACoarserRasterBilinearly) {
  const auto folder = test::fresh_folder("erodible_coarse");
  SceneInputs inputs = inputs_in(folder);
  RasterFixture erodible;  // 20 m cells over the same 400 x 300 m
  erodible.width = 20;
  erodible.height = 15;
  erodible.cell = 20.0;
  erodible.value = [](int c, int r) { return 0.1 * c + 0.05 * r; };
  write_raster(folder / "erodible.tif", erodible);
  inputs.erodible = folder / "erodible.tif";
  const Scene scene = load_scene(inputs);
  ASSERT_TRUE(scene.erodible.has_value());
  // DEM node (C, R) lies at column C / 2 - 0.25, row R / 2 - 0.25 of the coarse raster, where the
  // bilinear interpolant of a linear field is the field itself; inside the border ring, within
  // Float32 rounding (1e-5 m).
  for (int r = 2; r < 28; ++r) {
    for (int c = 2; c < 38; ++c) {
      const double expected = 0.1 * (c / 2.0 - 0.25) + 0.05 * (r / 2.0 - 0.25);
      ASSERT_NEAR(scene.erodible->at(c, r), expected, 1e-5) << "cell " << c << ", " << r;
    }
  }
}

TEST(SceneErodible, NamesAMissingOrUnreadableFile) {
  const auto folder = test::fresh_folder("erodible_bad");
  SceneInputs inputs = inputs_in(folder);
  inputs.erodible = folder / "missing.tif";
  std::string message = load_error(inputs);
  EXPECT_NE(message.find("missing.tif (erodible): file not found"), std::string::npos) << message;

  std::ofstream(folder / "notes.tif") << "not a raster\n";
  inputs.erodible = folder / "notes.tif";
  message = load_error(inputs);
  EXPECT_NE(message.find("notes.tif (erodible)"), std::string::npos) << message;
}

class MudflowRelease : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = test::fresh_folder("mudflow_release");
    inputs_ = inputs_in(folder_);
    inputs_.release_needs_depth = true;
  }
  static constexpr const char* kSquare =
      "POLYGON((500100 5199900,500200 5199900,500200 5199800,500100 5199800,500100 5199900))";
  std::filesystem::path folder_;
  SceneInputs inputs_;
};

TEST_F(MudflowRelease, RefusesPolygonsWithoutADepthAttribute) {
  test::write_vector(folder_ / "no_depth.gpkg", "EPSG:32632", {{kSquare, 0}}, false);
  inputs_.release = folder_ / "no_depth.gpkg";
  const std::string message = load_error(inputs_);
  EXPECT_NE(message.find("no_depth.gpkg (release): layer 'release' has no `depth` attribute"), std::string::npos) << message;

  // Rock fall takes the same layer (1 m where no depth is given).
  inputs_.release_needs_depth = false;
  EXPECT_NEAR(load_scene(inputs_).release->vertical_volume(), 100 * 100 * 1.0, 1e-6);
}

TEST_F(MudflowRelease, RefusesAFeatureOfZeroDepth) {
  test::write_vector(folder_ / "zero.gpkg", "EPSG:32632", {{kSquare, 1.5}, {"POINT(500250 5199850)", 0}}, true);
  inputs_.release = folder_ / "zero.gpkg";
  const std::string message = load_error(inputs_);
  EXPECT_NE(message.find("zero.gpkg (release): feature 2 of layer 'release' has no release depth"), std::string::npos)
      << message;
}

TEST_F(MudflowRelease, AcceptsDepthsFromAttributesAndRasters) {
  test::write_vector(folder_ / "depth.gpkg", "EPSG:32632", {{kSquare, -1.8}}, true);
  inputs_.release = folder_ / "depth.gpkg";
  EXPECT_NEAR(load_scene(inputs_).release->vertical_volume(), 100 * 100 * 1.8, 1e-3);  // Float32 depths: 1e-3 m3

  RasterFixture depth;
  depth.value = [](int c, int r) { return (c < 5 && r < 4) ? -1.5 : 0.0; };
  write_raster(folder_ / "depth.tif", depth);
  inputs_.release = folder_ / "depth.tif";
  EXPECT_NEAR(load_scene(inputs_).release->vertical_volume(), 20 * 100 * 1.5, 1e-6);
}

}  // namespace
}  // namespace talus::gis
