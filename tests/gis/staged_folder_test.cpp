// Tests of StagedFolder (issue 18, item 3; docs/layers.md, "How a set is committed"): the output
// folder is checked and staged before any work, a rerun replaces the old set whole (no stale
// layer stays), a folder of other files is refused, an uncommitted set leaves the old one as it
// was, staging folders of killed runs are cleared.
#include "talus/gis/staged_folder.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <fstream>
#include <set>

#include "talus/core/errors.hpp"
#include "test_paths.hpp"

namespace talus::gis {
namespace {

namespace fs = std::filesystem;

std::set<std::string> names_in(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename().string());
  return names;
}

void write(const fs::path& path, const std::string& text) { std::ofstream(path) << text; }

// A folder holding a Talus set: a run.json that says so, and a layer.
void old_set(const fs::path& folder) {
  fs::create_directories(folder);
  write(folder / "run.json", R"({"software": "talus", "seed": 1})");
  write(folder / "erosion_depth.tif", "old layer");
}

TEST(StagedFolder, ARerunReplacesTheOldSetWholeLeavingNoStaleLayer) {
  const auto root = test::fresh_folder("staged_rerun");
  old_set(root / "out");
  {
    StagedFolder folder(root / "out");
    EXPECT_EQ(folder.staging().parent_path(), fs::absolute(root));
    write(folder.staging() / "run.json", R"({"software": "talus", "seed": 2})");
    write(folder.staging() / "energy_max.tif", "new layer");
    EXPECT_EQ(names_in(root / "out"), (std::set<std::string>{"run.json", "erosion_depth.tif"}));  // old until commit
    folder.commit();
  }
  EXPECT_EQ(names_in(root / "out"), (std::set<std::string>{"run.json", "energy_max.tif"}));
  EXPECT_EQ(names_in(root), (std::set<std::string>{"out"}));  // the old set and the staging folder are gone
}

TEST(StagedFolder, AnUncommittedSetLeavesTheOldOneAndNothingElse) {
  const auto root = test::fresh_folder("staged_uncommitted");
  old_set(root / "out");
  {
    StagedFolder folder(root / "out");
    write(folder.staging() / "run.json", "{}");
  }
  EXPECT_EQ(names_in(root / "out"), (std::set<std::string>{"run.json", "erosion_depth.tif"}));
  EXPECT_EQ(names_in(root), (std::set<std::string>{"out"}));
  {
    StagedFolder folder(root / "new");  // a failed run on a new folder creates nothing
  }
  EXPECT_EQ(names_in(root), (std::set<std::string>{"out"}));
}

TEST(StagedFolder, RefusesAFileAFolderOfOtherFilesAndAFolderItCannotCreate) {
  const auto root = test::fresh_folder("staged_refused");
  write(root / "plain", "x");
  fs::create_directories(root / "mine");
  write(root / "mine" / "notes.txt", "a user's file");
  write(root / "mine" / "run.json", R"({"software": "something else"})");
  for (const fs::path& out : {root / "plain", root / "mine", root / "plain" / "below", fs::path("/proc/talus/out")}) {
    try {
      StagedFolder folder(out);
      ADD_FAILURE() << "no error for " << out;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find(out.string() + " (--out): "), std::string::npos) << error.what();
    }
  }
  EXPECT_EQ(names_in(root / "mine"), (std::set<std::string>{"notes.txt", "run.json"}));
  EXPECT_EQ(names_in(root), (std::set<std::string>{"plain", "mine"}));
}

TEST(StagedFolder, ClearsTheStagingFoldersOfKilledRunsButNotOfLiveOnes) {
  const auto root = test::fresh_folder("staged_abandoned");
  fs::create_directories(root / ".out.talus-999999999-abcdef");  // no such process
  const std::string live = ".out.talus-" + std::to_string(::getpid()) + "-ghijkl";
  fs::create_directories(root / live);
  {
    StagedFolder folder(root / "out");
    folder.commit();
  }
  EXPECT_EQ(names_in(root), (std::set<std::string>{"out", live}));
}

}  // namespace
}  // namespace talus::gis
