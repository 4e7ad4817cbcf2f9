// Runs the built `talus` program in a given working folder and captures what it printed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace talus::test {

struct ProgramResult {
  int exit_code = -1;
  std::string out;   // stdout
  std::string err;   // stderr
};

ProgramResult run_talus(const std::vector<std::string>& arguments, const std::filesystem::path& working_folder);

}  // namespace talus::test
