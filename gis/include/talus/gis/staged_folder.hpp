// The output folder of a run as one unit (issue 18, item 3; docs/layers.md, "How a set is
// committed"): every file of the set is written into a fresh hidden staging folder beside
// --out, created before any work (so a folder that cannot be written is refused first), and
// commit() puts it in --out's place with one atomic exchange of the two folders, so that at
// every instant --out holds either the old complete set or the new complete one, never a mix
// and never a stale layer of an earlier run.
#pragma once

#include <filesystem>
#include <vector>

namespace talus::gis {

class StagedFolder {
 public:
  // Checks --out (`out`) and creates the staging folder beside it. Throws InputError naming
  // `out` when it is a file, holds files that are not a Talus set (a folder of one is replaced
  // whole), or when its parent cannot be created or written. Removes staging folders that
  // killed runs left beside `out`. The parent folders it creates are removed again when the set
  // is never committed, so that a failed run leaves nothing it created.
  explicit StagedFolder(const std::filesystem::path& out);
  ~StagedFolder();  // removes the staging folder of a set that was never committed
  StagedFolder(const StagedFolder&) = delete;
  StagedFolder& operator=(const StagedFolder&) = delete;

  const std::filesystem::path& staging() const { return staging_; }
  const std::filesystem::path& out() const { return out_; }
  // Exchanges the staging folder with --out (or renames it there when --out does not exist)
  // and removes the old set.
  void commit();

 private:
  void remove_created_parents() const;  // those still empty, deepest first
  std::filesystem::path out_;
  std::vector<std::filesystem::path> created_parents_;  // deepest first
  std::filesystem::path staging_;
  bool committed_ = false;
};

}  // namespace talus::gis
