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

// A rockfall, mudflow or study run gets `--project off` unless its arguments name --project: the QGIS
// project and quicklooks take seconds per run, and tests/cli/run_project_test.cpp tests them.
ProgramResult run_talus(const std::vector<std::string>& arguments, const std::filesystem::path& working_folder);

// The same under `mpirun -np ranks` (OpenMPI, scripts/setup.sh; issue 19, item 6).
ProgramResult run_talus_mpi(int ranks, const std::vector<std::string>& arguments, const std::filesystem::path& working_folder);

// The lines of a run's stderr that are errors, `talus: error: ...` (progress lines are not).
std::vector<std::string> error_lines(const std::string& err);

}  // namespace talus::test
