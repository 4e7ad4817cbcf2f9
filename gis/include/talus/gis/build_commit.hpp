// The git commit the program was built from (cmake/TalusGitCommit.cmake): 40 hexadecimal digits,
// followed by "-modified" when tracked files differed from that commit, or "unknown" when the
// sources were not a git checkout. `talus --version` prints it and run.json records it beside
// the version (docs/layers.md, "run.json").
#pragma once

#include <string_view>

namespace talus::gis {

std::string_view git_commit();

}  // namespace talus::gis
