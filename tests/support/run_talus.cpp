#include "run_talus.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "test_paths.hpp"

namespace talus::test {
namespace {

std::string quoted(const std::string& text) {
  std::string q = "'";
  for (char c : text) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string slurp(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

// talus, or `launcher talus` (mpirun), with the arguments, its output captured.
ProgramResult run_with(const std::string& launcher, const std::vector<std::string>& arguments,
                       const std::filesystem::path& working_folder) {
  const auto capture = working_folder.parent_path() / ("capture-" + working_folder.filename().string());
  std::filesystem::create_directories(capture);
  std::string command = "cd " + quoted(working_folder.string()) + " && " + launcher + quoted(talus_exe().string());
  const bool simulates = !arguments.empty() && (arguments[0] == "rockfall" || arguments[0] == "mudflow" || arguments[0] == "study");
  const bool project_off = simulates && std::ranges::find(arguments, "--project") == arguments.end();
  for (std::size_t k = 0; k < arguments.size(); ++k) {
    command += " " + quoted(arguments[k]);
    if (k == 0 && project_off) command += " --project off";  // right after the subcommand
  }
  command += " >" + quoted((capture / "out").string()) + " 2>" + quoted((capture / "err").string());
  const int status = std::system(command.c_str());
  ProgramResult result;
  result.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  result.out = slurp(capture / "out");
  result.err = slurp(capture / "err");
  std::filesystem::remove_all(capture);
  return result;
}

}  // namespace

ProgramResult run_talus(const std::vector<std::string>& arguments, const std::filesystem::path& working_folder) {
  return run_with("", arguments, working_folder);
}

std::vector<std::string> error_lines(const std::string& err) {
  std::vector<std::string> lines;
  std::istringstream text(err);
  for (std::string line; std::getline(text, line);) {
    if (line.rfind("talus: error:", 0) == 0) lines.push_back(line);
  }
  return lines;
}

ProgramResult run_talus_mpi(int ranks, const std::vector<std::string>& arguments, const std::filesystem::path& working_folder) {
  // More ranks than cores, and as root in CI's containers: OpenMPI refuses both unless told.
  std::string launcher = "mpirun --oversubscribe -np " + std::to_string(ranks) + " ";
  if (geteuid() == 0) launcher += "--allow-run-as-root ";
  return run_with(launcher, arguments, working_folder);
}

}  // namespace talus::test
