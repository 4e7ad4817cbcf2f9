// Paths the GIS and CLI tests need, compiled in by tests/CMakeLists.txt.
#pragma once

#include <filesystem>
#include <string>

namespace talus::test {

std::filesystem::path talus_exe();      // the built `talus` program
std::filesystem::path source_dir();     // the repository root
std::filesystem::path data_dir();       // data/: the real data sets, each with its licence
// A fresh, empty temporary folder for one test, private to this process.
std::filesystem::path fresh_folder(const std::string& name);

}  // namespace talus::test
