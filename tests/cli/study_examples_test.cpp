// The two studies docs/study.md documents run end to end (issue 19, "Done when"):
// sample_dem/study.toml and docs/examples/tirol_alr.study.toml, every scenario's layers by the
// layer contract (tests/support/layer_contract.hpp), the hazard map and study.json complete.
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "layer_contract.hpp"
#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

void expect_complete_study(const fs::path& study, std::size_t scenarios, const fs::path& dem) {
  const fs::path folder = test::fresh_folder("study_example_" + study.stem().string());
  const test::ProgramResult run = test::run_talus({"study", study.string(), "--out", "out"}, folder);
  ASSERT_EQ(run.exit_code, 0) << run.out << run.err;
  std::ifstream record_file(folder / "out/study.json");
  const nlohmann::json record = nlohmann::json::parse(record_file);
  ASSERT_EQ(record["scenarios"].size(), scenarios);
  for (const auto& s : record["scenarios"]) {
    EXPECT_EQ(test::layer_contract_problems(s["process"].get<std::string>(), folder / "out" / s["folder"].get<std::string>(), dem),
              test::kNoProblems)
        << s["name"];
  }
  EXPECT_TRUE(fs::exists(folder / "out/hazard/hazard.tif"));
  EXPECT_TRUE(fs::exists(folder / "out/hazard/hazard_zones.gpkg"));
  EXPECT_GT(record["hazard"]["maps"]["hazard"][0]["cells"].get<int>(), 0) << "no cell of high hazard";
}

TEST(StudyExamples, TheSampleStudyRunsEndToEnd) {
  expect_complete_study(test::source_dir() / "sample_dem/study.toml", 4, test::source_dir() / "sample_dem/dem.tif");
}

TEST(StudyExamples, TheTirolStudyRunsEndToEnd) {
  expect_complete_study(test::source_dir() / "docs/examples/tirol_alr.study.toml", 4,
                        test::data_dir() / "tirol_alr/avaAlr.tif");
}

}  // namespace
}  // namespace talus
