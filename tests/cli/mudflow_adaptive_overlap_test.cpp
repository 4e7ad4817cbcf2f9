// Adaptive particles against uniform finest particles on the sample scene (issue 5, "Tests"):
// `talus mudflow` with 1.25 m particles, adaptive (released at 5 m, fission down to 1.25 m where
// the pressure varies, fusion where the flow is calm, individual time steps) and uniform (every
// particle 1.25 m, one global step), every other parameter at its default, each run until the
// flow stops (--duration 600: the energy criterion ends both). Their deposit areas must overlap
// with an IoU of at least 0.84.
//
// Why 1.25 m and 0.84: the IoU of two uniform runs that differ only in the seed (the release
// jitter) is the noise floor of the metric. With the default material's yield stress (issue 37)
// it is 0.857 at 1.25 m, 0.809 at 2.5 m and 0.755 at 5 m (docs/mudflow-speed-accuracy.md,
// 2026-12-06): a lobe stops whole where a few of its particles fall below the stopping depth.
// Adaptive against uniform measured 0.850 there, within that floor; the bar is 0.98 of it.
// (Before, with no yield stress, the floor was 0.915 and the bar 0.86.) The two runs take about
// 25 s and 10 s of one core.
#include <gtest/gtest.h>

#include <cstddef>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "raster_fixtures.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

// m: a cell holds deposit above this depth (the sweep's threshold, docs/mudflow-speed-accuracy.md).
constexpr float kDepositThreshold = 0.05f;

test::ProgramResult run_sample(const fs::path& out, const fs::path& root, const std::string& adaptive) {
  const auto sample = test::source_dir() / "sample_dem";
  return test::run_talus({"mudflow", "--dem", (sample / "dem.tif").string(), "--lithology",
                          (sample / "lithology.tif").string(), "--vegetation", (sample / "vegetation.tif").string(),
                          "--release", (sample / "mudflow_release.gpkg").string(), "--out", out.string(),
                          "--particle-size", "1.25", "--adaptive", adaptive, "--seed", "1", "--threads", "1",
                          "--duration", "600"},
                         root);
}

std::uint64_t particle_steps(const fs::path& out) {
  std::ifstream file(out / "run.json");
  return nlohmann::json::parse(file)["counts"]["particle_steps"].get<std::uint64_t>();
}

TEST(MudflowAdaptiveOverlap, AdaptiveDepositMatchesUniformFinestParticles) {
  const fs::path root = test::fresh_folder("mudflow_adaptive_overlap");
  const test::ProgramResult uniform = run_sample(root / "uniform", root, "off");
  ASSERT_EQ(uniform.exit_code, 0) << uniform.err;
  const test::ProgramResult adaptive = run_sample(root / "adaptive", root, "on");
  ASSERT_EQ(adaptive.exit_code, 0) << adaptive.err;

  const std::vector<float> reference = test::read_band(root / "uniform" / "deposit_depth.tif");
  const std::vector<float> deposit = test::read_band(root / "adaptive" / "deposit_depth.tif");
  ASSERT_EQ(deposit.size(), reference.size());
  std::size_t both = 0, either = 0;
  for (std::size_t cell = 0; cell < deposit.size(); ++cell) {
    const bool a = deposit[cell] > kDepositThreshold, b = reference[cell] > kDepositThreshold;
    both += a && b ? 1 : 0;
    either += a || b ? 1 : 0;
  }
  ASSERT_GT(either, 1000u);  // the deposit covers about 2450 cells of 25 m2
  const double iou = static_cast<double>(both) / static_cast<double>(either);
  RecordProperty("deposit_iou", std::to_string(iou));
  // 0.84: 0.98 of the seed-to-seed floor 0.857 (measured 0.850, 2026-12-06).
  EXPECT_GE(iou, 0.84) << both << " of " << either << " cells";
  // The adaptivity does its work: 4.1 times fewer particle-steps (9.2 million against 38.2).
  EXPECT_LT(2.5 * static_cast<double>(particle_steps(root / "adaptive")),
            static_cast<double>(particle_steps(root / "uniform")));
  fs::remove_all(root);
}

}  // namespace
}  // namespace talus
