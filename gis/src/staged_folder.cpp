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

namespace talus::gis {
namespace {

// ".NAME.talus-": the start of every staging folder of --out NAME.
std::string staging_prefix(const std::filesystem::path& out) { return "." + out.filename().string() + ".talus-"; }

// A folder is a Talus set when its run.json says so ("software": "talus").
bool is_talus_set(const std::filesystem::path& folder) {
  std::ifstream in(folder / "run.json");
  if (!in) return false;
  const nlohmann::json record = nlohmann::json::parse(in, nullptr, false);
  return record.is_object() && record.value("software", "") == "talus";
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
  std::error_code ignored;
  std::filesystem::remove_all(staging_, ignored);  // the old set, now under the staging name
}

}  // namespace talus::gis
