// Nothing of the user's is lost (issue 38, item 6; docs/layers.md, "Files of yours in an output
// folder"): a rerun of `talus rockfall` into its folder keeps the notes and reports a user put
// there, refuses with one line a rerun over a layer file the user changed, refuses an immutable
// folder before any work, and gives the folder a plain mkdir's permissions.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>

#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> sample_run(const fs::path& out, const std::string& seed) {
  const fs::path sample = test::source_dir() / "sample_dem";
  return {"rockfall", "--dem", (sample / "dem.tif").string(), "--release", (sample / "rockfall_release.gpkg").string(),
          "--runs", "1", "--seed", seed, "--project", "off", "--out", out.string()};
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

TEST(UsersFiles, ARerunKeepsThemAndRefusesToReplaceAnEditedFile) {
  const auto work = test::fresh_folder("users_files");
  const fs::path out = work / "out";
  const mode_t umask_before = ::umask(027);
  const auto first = test::run_talus(sample_run(out, "1"), work);
  ::umask(umask_before);
  ASSERT_EQ(first.exit_code, 0) << first.err;
  struct stat info{};
  ASSERT_EQ(::stat(out.c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 07777, 0750u) << "not a plain mkdir's permissions under umask 027";

  write(out / "notes.txt", "checked on site 2026-12-01");
  fs::create_directories(out / "report");
  write(out / "report" / "hazard.pdf", "%PDF");
  const auto second = test::run_talus(sample_run(out, "2"), work);
  ASSERT_EQ(second.exit_code, 0) << second.err;
  EXPECT_TRUE(fs::exists(out / "notes.txt"));
  EXPECT_TRUE(fs::exists(out / "report" / "hazard.pdf"));
  EXPECT_TRUE(fs::exists(out / "energy_max.tif"));

  write(out / "energy_max.qml", "<qgis>the user's own style</qgis>");
  const auto third = test::run_talus(sample_run(out, "3"), work);
  EXPECT_EQ(third.exit_code, 2) << third.err;
  EXPECT_EQ(test::error_lines(third.err).size(), 1u) << third.err;
  EXPECT_NE(third.err.find("(--out): energy_max.qml was changed since Talus wrote it"), std::string::npos) << third.err;
  EXPECT_EQ(third.err.find("Progress"), std::string::npos) << "refused only after work:\n" << third.err;
  std::ifstream style(out / "energy_max.qml");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(style), {}), "<qgis>the user's own style</qgis>");
}

TEST(UsersFiles, AnImmutableFolderIsRefusedBeforeAnyWork) {
  const auto work = test::fresh_folder("users_files_immutable");
  const fs::path out = work / "out";
  ASSERT_EQ(test::run_talus(sample_run(out, "1"), work).exit_code, 0);
  if (std::system(("chattr +i '" + out.string() + "' 2>/dev/null").c_str()) != 0) {
    GTEST_SKIP() << "chattr +i is not allowed here";
  }
  const auto result = test::run_talus(sample_run(out, "2"), work);
  EXPECT_EQ(std::system(("chattr -i '" + out.string() + "'").c_str()), 0);
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(test::error_lines(result.err).size(), 1u) << result.err;
  EXPECT_NE(result.err.find("(--out): cannot be replaced: the folder is immutable"), std::string::npos) << result.err;
  EXPECT_EQ(result.err.find("Progress"), std::string::npos) << "refused only after work:\n" << result.err;
  for (const auto& entry : fs::directory_iterator(work)) EXPECT_EQ(entry.path(), out) << "left beside the folder";
}

}  // namespace
}  // namespace talus
