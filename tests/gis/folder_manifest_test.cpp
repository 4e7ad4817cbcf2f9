// Tests of the output folder's manifest (issue 38, item 6; docs/layers.md, "Files of yours in an
// output folder"): after a set is written, a file or folder a user adds is foreign, a file of
// the set changed in size or in content is changed, a copy of the set (new modification times,
// same bytes) is unchanged, and GIS side files of a layer (.aux.xml) belong to the layer.
#include "talus/gis/folder_manifest.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include <nlohmann/json.hpp>

#include "test_paths.hpp"

namespace talus::gis {
namespace {

namespace fs = std::filesystem;

void write(const fs::path& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

std::vector<std::string> names(const std::vector<fs::path>& paths) {
  std::vector<std::string> text;
  for (const fs::path& path : paths) text.push_back(path.generic_string());
  return text;
}

// A set of two layers and a quicklook, with its manifest.
fs::path written_set(const std::string& name) {
  const fs::path folder = test::fresh_folder(name);
  write(folder / "energy_max.tif", "layer bytes");
  write(folder / "run.json", R"({"software": "talus"})");
  fs::create_directories(folder / "quicklook");
  write(folder / "quicklook" / "intensity.png", "png bytes");
  write_folder_manifest(folder);
  return folder;
}

TEST(FolderManifest, AFreshSetHoldsNothingForeignOrChanged) {
  const fs::path folder = written_set("manifest_fresh");
  const FolderSurvey survey = survey_folder(folder);
  EXPECT_TRUE(survey.recorded);
  EXPECT_TRUE(survey.foreign.empty()) << list_of_names(survey.foreign);
  EXPECT_TRUE(survey.changed.empty()) << list_of_names(survey.changed);
}

TEST(FolderManifest, TellsTheUsersFilesAndChangesFromTheSetsFiles) {
  const fs::path folder = written_set("manifest_user");
  write(folder / "notes.txt", "field notes");
  fs::create_directories(folder / "report" / "figures");
  write(folder / "report" / "figures" / "a.pdf", "pdf");
  write(folder / "quicklook" / "annotated.png", "the user's");
  write(folder / "energy_max.tif.aux.xml", "<PAMDataset/>");  // QGIS's statistics of the layer
  write(folder / "run.json", R"({"software": "talus", "edited": true})");  // longer
  const auto later = fs::last_write_time(folder / "energy_max.tif") + std::chrono::seconds(5);
  write(folder / "energy_max.tif", "LAYER BYTES");  // same size, other bytes
  fs::last_write_time(folder / "energy_max.tif", later);
  const FolderSurvey survey = survey_folder(folder);
  EXPECT_EQ(names(survey.foreign), (std::vector<std::string>{"notes.txt", "quicklook/annotated.png", "report"}));
  EXPECT_EQ(names(survey.changed), (std::vector<std::string>{"energy_max.tif", "run.json"}));
  EXPECT_EQ(changed_since_written(survey.changed),
            "energy_max.tif, run.json were changed since Talus wrote them, and a rerun would replace them: move them "
            "out of the folder, or give another --out");
}

TEST(FolderManifest, ACopiedSetWithNewTimesIsUnchanged) {
  const fs::path folder = written_set("manifest_copied");
  const fs::path copy = test::fresh_folder("manifest_copy") / "set";
  fs::copy(folder, copy, fs::copy_options::recursive);
  for (const auto& entry : fs::recursive_directory_iterator(copy)) {
    if (entry.is_regular_file()) fs::last_write_time(entry.path(), fs::last_write_time(entry.path()) + std::chrono::hours(1));
  }
  const FolderSurvey survey = survey_folder(copy);
  EXPECT_TRUE(survey.recorded);
  EXPECT_TRUE(survey.foreign.empty()) << list_of_names(survey.foreign);
  EXPECT_TRUE(survey.changed.empty()) << list_of_names(survey.changed);
}

// A study's folder holds the sets of its scenarios, each with its manifest: the study's manifest
// takes their checksums for files whose stamps still match instead of reading them again.
TEST(FolderManifest, TakesTheChecksumsOfNestedSetsWhoseFilesAreUnchanged) {
  const fs::path study = test::fresh_folder("manifest_nested");
  fs::create_directories(study / "scenarios");
  fs::copy(written_set("manifest_nested_set"), study / "scenarios" / "a", fs::copy_options::recursive);
  const fs::path set = study / "scenarios" / "a";
  write_folder_manifest(set);
  std::ifstream in(set / kFolderManifestName);
  nlohmann::json nested = nlohmann::json::parse(in);
  in.close();
  nested["files"]["run.json"]["sha256"] = "taken from the nested manifest";
  std::ofstream(set / kFolderManifestName) << nested.dump();
  write_folder_manifest(study);
  std::ifstream root(study / kFolderManifestName);
  const nlohmann::json manifest = nlohmann::json::parse(root);
  EXPECT_EQ(manifest["files"]["scenarios/a/run.json"]["sha256"], "taken from the nested manifest");
  EXPECT_EQ(manifest["files"]["scenarios/a/energy_max.tif"]["sha256"], nested["files"]["energy_max.tif"]["sha256"]);
}

TEST(FolderManifest, AFolderWithoutAManifestIsNotRecorded) {
  const fs::path folder = test::fresh_folder("manifest_none");
  write(folder / "run.json", R"({"software": "talus"})");
  const FolderSurvey survey = survey_folder(folder);
  EXPECT_FALSE(survey.recorded);
  EXPECT_TRUE(survey.foreign.empty());
}

TEST(FolderManifest, ListsAtMostFiveNames) {
  const std::vector<fs::path> paths = {"a", "b", "c", "d", "e", "f", "g"};
  EXPECT_EQ(list_of_names(paths), "a, b, c, d, e and 2 more");
  EXPECT_EQ(changed_since_written({"project.qgz"}),
            "project.qgz was changed since Talus wrote it, and a rerun would replace it: move it out of the folder, "
            "or give another --out");
}

}  // namespace
}  // namespace talus::gis
