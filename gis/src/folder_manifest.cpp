// The manifest of an output folder's own files (folder_manifest.hpp).
#include "talus/gis/folder_manifest.hpp"

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "talus/gis/run_record.hpp"

namespace talus::gis {
namespace {

// Size (bytes) and modification time (ns since 1970) of a file, as stat(2) gives them.
struct FileStamp {
  std::uint64_t size = 0;
  std::int64_t modified_ns = 0;
};

FileStamp stamp_of(const std::filesystem::path& file) {
  struct stat info{};
  if (::stat(file.c_str(), &info) != 0) throw std::runtime_error("cannot read " + file.string());
  return {static_cast<std::uint64_t>(info.st_size),
          static_cast<std::int64_t>(info.st_mtim.tv_sec) * 1000000000 + info.st_mtim.tv_nsec};
}

// Every regular file under `folder` but the manifest, relative to it, in name order.
std::vector<std::filesystem::path> files_under(const std::filesystem::path& folder) {
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(folder)) {
    if (!entry.is_regular_file()) continue;
    const std::filesystem::path relative = entry.path().lexically_relative(folder);
    if (relative != kFolderManifestName) files.push_back(relative);
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Files GIS software makes beside one it has opened, named after it.
constexpr std::array kDerivedSuffixes{".aux.xml", ".ovr", "-wal", "-shm", "-journal"};

bool derived_from_listed(const std::string& name, const std::set<std::string>& listed) {
  for (const std::string suffix : kDerivedSuffixes) {
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0 &&
        listed.count(name.substr(0, name.size() - suffix.size())) != 0) {
      return true;
    }
  }
  return false;
}

// The checksums the manifests of sets inside `folder` already hold (a study's scenarios), by the
// files' paths relative to `folder`, with the stamps they were taken at.
std::map<std::string, nlohmann::json> nested_records(const std::filesystem::path& folder,
                                                     const std::vector<std::filesystem::path>& files) {
  std::map<std::string, nlohmann::json> records;
  for (const std::filesystem::path& relative : files) {
    if (relative.filename() != kFolderManifestName) continue;
    std::ifstream in(folder / relative);
    const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
    if (!manifest.is_object() || !manifest.contains("files") || !manifest["files"].is_object()) continue;
    for (const auto& [name, record] : manifest["files"].items()) {
      records[(relative.parent_path() / name).generic_string()] = record;
    }
  }
  return records;
}

}  // namespace

void write_folder_manifest(const std::filesystem::path& folder) {
  const std::vector<std::filesystem::path> all = files_under(folder);
  const std::map<std::string, nlohmann::json> known = nested_records(folder, all);
  nlohmann::ordered_json files = nlohmann::ordered_json::object();
  for (const std::filesystem::path& relative : all) {
    const std::string name = relative.generic_string();
    const FileStamp stamp = stamp_of(folder / relative);
    // A file a nested set's manifest holds unchanged keeps its checksum: hashed once, not again.
    const auto record = known.find(name);
    const bool unchanged = record != known.end() && record->second.value("bytes", std::uint64_t{0}) == stamp.size &&
                           record->second.value("modified_ns", std::int64_t{0}) == stamp.modified_ns;
    files[name] = {{"bytes", stamp.size},
                   {"modified_ns", stamp.modified_ns},
                   {"sha256", unchanged ? record->second.value("sha256", std::string()) : sha256_of_file(folder / relative)}};
  }
  const nlohmann::ordered_json manifest = {
      {"software", "talus"},
      {"meaning", "the files Talus wrote here; a later run into this folder keeps every other file"},
      {"files", files}};
  std::ofstream out(folder / kFolderManifestName, std::ios::binary);
  out << manifest.dump(1) << '\n';
  out.close();
  if (!out) throw std::runtime_error("cannot write " + (folder / kFolderManifestName).string());
}

FolderSurvey survey_folder(const std::filesystem::path& folder) {
  FolderSurvey survey;
  std::ifstream in(folder / kFolderManifestName);
  if (!in) return survey;
  const nlohmann::json manifest = nlohmann::json::parse(in, nullptr, false);
  if (!manifest.is_object() || !manifest.contains("files") || !manifest["files"].is_object()) return survey;
  survey.recorded = true;
  std::set<std::string> listed;
  std::set<std::string> listed_folders;  // every folder above a listed file
  for (const auto& [name, record] : manifest["files"].items()) {
    listed.insert(name);
    for (auto up = std::filesystem::path(name).parent_path(); !up.empty(); up = up.parent_path()) {
      listed_folders.insert(up.generic_string());
    }
  }
  for (auto entry = std::filesystem::recursive_directory_iterator(folder);
       entry != std::filesystem::recursive_directory_iterator(); ++entry) {
    const std::filesystem::path relative = entry->path().lexically_relative(folder);
    const std::string name = relative.generic_string();
    if (name == kFolderManifestName) continue;
    if (entry->is_directory() && !entry->is_symlink()) {
      if (listed_folders.count(name) == 0) {
        survey.foreign.push_back(relative);  // a folder of the user's, kept whole
        entry.disable_recursion_pending();
      }
      continue;
    }
    if (listed.count(name) == 0) {
      if (!derived_from_listed(name, listed)) survey.foreign.push_back(relative);
      continue;
    }
    const nlohmann::json& record = manifest["files"][name];
    const FileStamp stamp = stamp_of(entry->path());
    if (stamp.size != record.value("bytes", std::uint64_t{0})) {
      survey.changed.push_back(relative);
    } else if (stamp.modified_ns != record.value("modified_ns", std::int64_t{0}) &&
               sha256_of_file(entry->path()) != record.value("sha256", std::string())) {
      survey.changed.push_back(relative);
    }
  }
  std::sort(survey.foreign.begin(), survey.foreign.end());
  std::sort(survey.changed.begin(), survey.changed.end());
  return survey;
}

std::string list_of_names(const std::vector<std::filesystem::path>& paths, std::size_t shown) {
  std::string text;
  for (std::size_t k = 0; k < paths.size() && k < shown; ++k) {
    if (k > 0) text += ", ";
    text += paths[k].generic_string();
  }
  if (paths.size() > shown) text += " and " + std::to_string(paths.size() - shown) + " more";
  return text;
}

std::string changed_since_written(const std::vector<std::filesystem::path>& changed) {
  const bool one = changed.size() == 1;
  return list_of_names(changed) + (one ? " was" : " were") + " changed since Talus wrote " + (one ? "it" : "them") +
         ", and a rerun would replace " + (one ? "it" : "them") + ": move " + (one ? "it" : "them") +
         " out of the folder, or give another --out";
}

}  // namespace talus::gis
