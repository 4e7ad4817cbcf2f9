// The layer contract (docs/architecture.md section 3, docs/layers.md): what every output folder
// of `talus rockfall` and `talus mudflow` must hold, checked file by file with GDAL.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace talus::test {

// One line per way in which the folder `out` breaks the contract, empty when it keeps it.
// `kind` is "rockfall" or "mudflow"; `dem` is the run's DEM, whose grid and CRS every layer
// must carry. The layers every run of the kind writes must be there; `intensity` and
// `erosion_depth`, which options turn off or on, are checked when present.
std::vector<std::string> layer_contract_problems(const std::string& kind, const std::filesystem::path& out,
                                                 const std::filesystem::path& dem);

// What layer_contract_problems returns for a folder that keeps the contract, for EXPECT_EQ.
inline const std::vector<std::string> kNoProblems;

}  // namespace talus::test
