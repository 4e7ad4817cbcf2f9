// Tests of StagedFolder (issue 18, item 3, and issue 38, item 6; docs/layers.md, "Writing as a
// unit"): the output folder is checked and staged before any work, a rerun replaces the old set
// whole (no stale layer stays) but keeps the files a user put beside it, files of the set changed
// since and folders that cannot be replaced are refused, a folder of other files is refused, an
// uncommitted set leaves the old one as it was, staging folders of killed runs are cleared, and
// the committed folder has a plain mkdir's permissions.
#include "talus/gis/staged_folder.hpp"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <set>

#include "talus/core/errors.hpp"
#include "talus/gis/folder_manifest.hpp"
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
  EXPECT_EQ(names_in(root / "out"), (std::set<std::string>{"run.json", "energy_max.tif", kFolderManifestName}));
  EXPECT_EQ(names_in(root), (std::set<std::string>{"out"}));  // the old set and the staging folder are gone
}

// A committed set: run.json, a layer and the manifest.
void committed_set(const fs::path& out, const std::string& seed) {
  StagedFolder folder(out);
  write(folder.staging() / "run.json", R"({"software": "talus", "seed": )" + seed + "}");
  write(folder.staging() / "energy_max.tif", "layer of seed " + seed);
  folder.commit();
}

TEST(StagedFolder, ARerunKeepsTheFilesAUserPutBesideTheSet) {
  const auto root = test::fresh_folder("staged_users_files");
  committed_set(root / "out", "1");
  write(root / "out" / "notes.txt", "field notes");
  fs::create_directories(root / "out" / "report");
  write(root / "out" / "report" / "hazard.pdf", "pdf");
  write(root / "out" / "energy_max.tif.aux.xml", "<PAMDataset/>");  // QGIS's statistics of the old layer
  {
    StagedFolder folder(root / "out");
    write(folder.staging() / "run.json", R"({"software": "talus", "seed": 2})");
    write(folder.staging() / "energy_max.tif", "layer of seed 2");
    write(folder.staging() / "notes.txt", "a file of the new set with the user's name");
    write(root / "out" / "late.txt", "written while the run ran");
    folder.commit();
  }
  EXPECT_EQ(names_in(root / "out"), (std::set<std::string>{"run.json", "energy_max.tif", kFolderManifestName, "notes.txt",
                                                           "notes.txt.kept", "report", "late.txt"}));
  std::ifstream kept(root / "out" / "notes.txt.kept");
  EXPECT_EQ(std::string(std::istreambuf_iterator<char>(kept), {}), "field notes");
  EXPECT_TRUE(fs::exists(root / "out" / "report" / "hazard.pdf"));
  EXPECT_EQ(names_in(root), (std::set<std::string>{"out"}));
}

TEST(StagedFolder, RefusesARerunOverFilesOfTheSetChangedSince) {
  const auto root = test::fresh_folder("staged_changed");
  committed_set(root / "out", "1");
  write(root / "out" / "run.json", R"({"software": "talus", "seed": 1, "note": "edited by hand"})");
  try {
    StagedFolder folder(root / "out");
    ADD_FAILURE() << "no error";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("(--out): run.json was changed since Talus wrote it"), std::string::npos)
        << error.what();
  }
  EXPECT_EQ(names_in(root), (std::set<std::string>{"out"}));
}

TEST(StagedFolder, TheCommittedFolderHasAPlainMkdirsPermissions) {
  const auto root = test::fresh_folder("staged_permissions");
  const mode_t before = ::umask(027);
  committed_set(root / "out", "1");
  ::umask(before);
  struct stat info{};
  ASSERT_EQ(::stat((root / "out").c_str(), &info), 0);
  EXPECT_EQ(info.st_mode & 07777, 0750u);
}

// chattr(1) sets a file's immutable flag where the file system and the user's rights allow it.
bool set_immutable(const fs::path& path, bool on) {
  const std::string command = std::string("chattr ") + (on ? "+i" : "-i") + " '" + path.string() + "' 2>/dev/null";
  return std::system(command.c_str()) == 0;
}

TEST(StagedFolder, RefusesAnImmutableFolderOrLayerBeforeAnyWork) {
  const auto root = test::fresh_folder("staged_immutable");
  committed_set(root / "out", "1");
  for (const fs::path& locked : {root / "out", root / "out" / "energy_max.tif"}) {
    if (!set_immutable(locked, true)) GTEST_SKIP() << "chattr +i is not allowed here";
    try {
      StagedFolder folder(root / "out");
      ADD_FAILURE() << "no error for " << locked;
    } catch (const InputError& error) {
      EXPECT_NE(std::string(error.what()).find("(--out): cannot be replaced: "), std::string::npos) << error.what();
      EXPECT_NE(std::string(error.what()).find("immutable"), std::string::npos) << error.what();
    }
    EXPECT_TRUE(set_immutable(locked, false));
  }
  EXPECT_EQ(names_in(root), (std::set<std::string>{"out"}));
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

TEST(StagedFolder, AnOldSetLeftByARunKilledWhileCommittingGivesTheUserTheirFiles) {
  const auto root = test::fresh_folder("staged_killed_commit");
  committed_set(root / "out", "2");
  committed_set(root / "old", "1");  // the earlier set, as the killed run's exchange left it
  write(root / "old" / "notes.txt", "field notes");
  fs::rename(root / "old", root / ".out.talus-999999999-abcdef");  // no such process
  {
    StagedFolder folder(root / "out");
    EXPECT_TRUE(fs::exists(root / "out" / "notes.txt"));
  }
  EXPECT_EQ(names_in(root), (std::set<std::string>{"out"}));
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
