// A run's output folder staged beside --out and swapped in whole (staged_folder.hpp).
#include "talus/gis/staged_folder.hpp"

#include <fcntl.h>
#include <signal.h>
#include <stdio.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include <nlohmann/json.hpp>

#include "talus/core/errors.hpp"
#include "talus/gis/folder_manifest.hpp"
#include "talus/gis/replaceable_output.hpp"

namespace talus::gis {
namespace {

// ".NAME.talus-": the start of every staging folder of --out NAME.
std::string staging_prefix(const std::filesystem::path& out) { return "." + out.filename().string() + ".talus-"; }

// A folder is a Talus set when its run.json or its manifest says so ("software": "talus").
bool is_talus_set(const std::filesystem::path& folder) {
  for (const char* name : {"run.json", kFolderManifestName}) {
    std::ifstream in(folder / name);
    if (!in) continue;
    const nlohmann::json record = nlohmann::json::parse(in, nullptr, false);
    if (record.is_object() && record.value("software", "") == "talus") return true;
  }
  return false;
}

// Moves what the old set holds beside Talus's unchanged files (the user's notes, a PDF, a
// project edited during the run) into the new set. One whose name the new set uses too is kept
// as NAME.kept (NAME.kept-2, ...). In a set without a manifest (written by a Talus that kept
// none) every file counts as Talus's.
void keep_users_files(const std::filesystem::path& old_set, const std::filesystem::path& new_set) {
  FolderSurvey survey = survey_folder(old_set);
  survey.foreign.insert(survey.foreign.end(), survey.changed.begin(), survey.changed.end());
  for (const std::filesystem::path& relative : survey.foreign) {
    std::filesystem::path target = new_set / relative;
    for (int copy = 1; std::filesystem::exists(std::filesystem::symlink_status(target)); ++copy) {
      target = new_set / relative;
      target += copy == 1 ? ".kept" : ".kept-" + std::to_string(copy);
    }
    std::error_code error;
    std::filesystem::create_directories(target.parent_path(), error);
    std::filesystem::rename(old_set / relative, target, error);
    if (error) {
      throw std::runtime_error("cannot keep " + relative.string() + " of the earlier set: it stays in " +
                               old_set.string() + " (" + error.message() + ")");
    }
  }
}

// Staging folders of runs whose process is gone (killed), named .NAME.talus-PID-XXXXXX.
void remove_abandoned_staging(const std::filesystem::path& out) {
  const std::string prefix = staging_prefix(out);
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(out.parent_path(), error)) {
    const std::string name = entry.path().filename().string();
    if (name.rfind(prefix, 0) != 0) continue;
    const long pid = std::strtol(name.c_str() + prefix.size(), nullptr, 10);
    if (pid > 0 && (::kill(static_cast<pid_t>(pid), 0) == 0 || errno != ESRCH)) continue;  // still running
    // An earlier set a run was killed in the middle of committing over may hold the user's files:
    // they move into --out first, or the folder stays.
    try {
      const FolderSurvey survey = survey_folder(entry.path());
      if (!survey.foreign.empty() || !survey.changed.empty()) {
        if (!std::filesystem::is_directory(out)) continue;
        keep_users_files(entry.path(), out);
      }
    } catch (const std::exception&) {
      continue;
    }
    std::error_code ignored;
    std::filesystem::remove_all(entry.path(), ignored);
  }
}

}  // namespace

StagedFolder::StagedFolder(const std::filesystem::path& out) {
  const std::string shown = out.string();
  std::error_code error;
  out_ = std::filesystem::absolute(out, error).lexically_normal();
  if (!out_.has_filename()) out_ = out_.parent_path();  // a trailing '/'
  std::error_code not_a_link;  // also set when nothing is there yet
  if (std::filesystem::is_symlink(out_, not_a_link)) out_ = std::filesystem::canonical(out_, error);
  if (error || out_.filename().empty() || out_.filename() == "." || out_.filename() == ".." || out_ == out_.root_path())
    throw InputError(shown + " (--out): not a folder Talus can replace");
  if (std::filesystem::exists(out_, error)) {
    if (!std::filesystem::is_directory(out_, error)) throw InputError(shown + " (--out): exists and is not a folder");
    if (!std::filesystem::is_empty(out_, error) && !is_talus_set(out_)) {
      throw InputError(shown + " (--out): holds files that are not a Talus layer set (no run.json of Talus); "
                               "a run replaces its folder whole, so give a new or empty folder");
    }
    check_replaceable_folder(out_, shown + " (--out)");
    FolderSurvey survey;
    try {
      survey = survey_folder(out_);
    } catch (const std::exception& e) {
      throw InputError(shown + " (--out): cannot read what it holds: " + e.what());
    }
    if (!survey.changed.empty()) {
      throw InputError(shown + " (--out): " + changed_since_written(survey.changed));
    }
  }
  for (auto folder = out_.parent_path(); !std::filesystem::exists(folder, error) && folder != folder.root_path();
       folder = folder.parent_path()) {
    created_parents_.push_back(folder);
  }
  std::filesystem::create_directories(out_.parent_path(), error);
  if (error) {
    remove_created_parents();
    throw InputError(shown + " (--out): cannot create " + out_.parent_path().string() + ": " + error.message());
  }
  remove_abandoned_staging(out_);
  std::string pattern = (out_.parent_path() / (staging_prefix(out_) + std::to_string(::getpid()) + "-XXXXXX")).string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    remove_created_parents();
    throw InputError(shown + " (--out): cannot write into " + out_.parent_path().string() + ": " + std::strerror(errno));
  }
  staging_ = pattern;
  std::filesystem::permissions(staging_, plain_folder_permissions(), error);  // mkdtemp's are 0700
}

StagedFolder::~StagedFolder() {
  if (committed_) return;
  std::error_code ignored;
  std::filesystem::remove_all(staging_, ignored);
  remove_created_parents();
}

void StagedFolder::remove_created_parents() const {
  std::error_code ignored;
  for (const auto& folder : created_parents_) std::filesystem::remove(folder, ignored);  // only while empty
}

void StagedFolder::commit() {
  write_folder_manifest(staging_);
  std::error_code error;
  if (!std::filesystem::exists(out_, error)) {
    std::filesystem::rename(staging_, out_, error);
    if (error) throw std::runtime_error("cannot rename " + staging_.string() + " to " + out_.string() + ": " + error.message());
  } else if (::renameat2(AT_FDCWD, staging_.c_str(), AT_FDCWD, out_.c_str(), RENAME_EXCHANGE) != 0) {
    if (errno != EINVAL && errno != ENOSYS) {
      throw std::runtime_error("cannot put " + staging_.string() + " in the place of " + out_.string() + ": " +
                               std::strerror(errno));
    }
    // A file system without atomic exchange: the old set moves aside first, so for the instant
    // between the two renames --out is missing (the old set lies complete beside it).
    const std::filesystem::path aside = staging_.string() + "-old";
    std::filesystem::rename(out_, aside, error);
    if (!error) std::filesystem::rename(staging_, out_, error);
    if (error) throw std::runtime_error("cannot replace " + out_.string() + ": " + error.message());
    staging_ = aside;
  }
  committed_ = true;
  keep_users_files(staging_, out_);  // the old set now lies under the staging name
  std::error_code ignored;
  std::filesystem::remove_all(staging_, ignored);
}

}  // namespace talus::gis
