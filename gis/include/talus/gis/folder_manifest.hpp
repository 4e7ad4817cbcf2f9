// The record of the files Talus wrote into an output folder (docs/layers.md, "Files of yours in
// an output folder"): `.talus-files.json` lists each file of the set with its size, modification
// time and SHA-256, so that a later run into the same folder tells Talus's own files from those
// a user put there (notes, a PDF) or changed since (an edited project), and keeps them.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace talus::gis {

inline constexpr const char* kFolderManifestName = ".talus-files.json";

// Writes the manifest of every file under `folder` (paths relative to it). Called on a complete
// set just before it is committed, when the folder holds nothing but Talus's files.
void write_folder_manifest(const std::filesystem::path& folder);

// What a folder holds beside the files its manifest lists unchanged. Paths are relative to the
// folder. `recorded` is false for a folder without a manifest (written by a Talus before it kept
// one); then `foreign` and `changed` are empty.
struct FolderSurvey {
  bool recorded = false;
  std::vector<std::filesystem::path> foreign;  // files and folders Talus did not write
  std::vector<std::filesystem::path> changed;  // files Talus wrote that were changed since
};

// Compares `folder` with its manifest. A file the manifest lists counts as unchanged when its
// size and modification time match, or else when its SHA-256 does (a copied folder). A file
// that GIS software derives from one of the set's files (`.aux.xml` statistics, `.ovr`
// overviews, SQLite's `-wal`, `-shm` and `-journal`) describes that file and belongs to it. A
// folder holding no listed file is reported whole.
FolderSurvey survey_folder(const std::filesystem::path& folder);

// "a, b and 3 more": at most `shown` names of `paths`, for a one-line message.
std::string list_of_names(const std::vector<std::filesystem::path>& paths, std::size_t shown = 5);

// The refusal of a rerun over files of a set that were changed since it was written.
std::string changed_since_written(const std::vector<std::filesystem::path>& changed);

}  // namespace talus::gis
