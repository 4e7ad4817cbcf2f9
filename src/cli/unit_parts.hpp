// Resume within a scenario (issue 19, item 5; docs/study.md, "Resume"): a rock fall's units of
// work (a tile's chunk of sources) each committed to a file of their own as they finish, so that
// a study killed at any moment and run again recomputes only the units that were not committed.
// The folder's key.json holds what the units' results depend on (the scenario's record and the
// cut into units); a folder with another key is emptied first.
#pragma once

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace talus::cli {

class UnitParts {
 public:
  // For this rank of `ranks` ranks; units of another rank count are not this run's.
  UnitParts(std::filesystem::path folder, int rank, int ranks) : folder_(std::move(folder)), rank_(rank), ranks_(ranks) {}

  // Rank 0: empties the folder unless its key.json holds `key`, then writes key.json.
  void prepare(const std::string& key) const;
  // The committed result of unit (tile, chunk) of this rank, if any.
  std::optional<std::vector<std::uint8_t>> load(std::size_t tile, std::size_t chunk) const;
  // Commits the unit's result: written under a temporary name, then renamed.
  void commit(std::size_t tile, std::size_t chunk, const std::vector<std::uint8_t>& bytes) const;

 private:
  std::filesystem::path file(std::size_t tile, std::size_t chunk) const;
  std::filesystem::path folder_;
  int rank_, ranks_;
};

}  // namespace talus::cli
