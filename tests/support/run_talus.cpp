#include "run_talus.hpp"

#include <sys/wait.h>

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

}  // namespace

ProgramResult run_talus(const std::vector<std::string>& arguments, const std::filesystem::path& working_folder) {
  const auto capture = working_folder.parent_path() / ("capture-" + working_folder.filename().string());
  std::filesystem::create_directories(capture);
  std::string command = "cd " + quoted(working_folder.string()) + " && " + quoted(talus_exe().string());
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

int check_layers(const std::string& kind, const std::filesystem::path& out, const std::filesystem::path& dem) {
  const auto checker = shared_dir() / "tools/check_layers.py";
  const std::string command =
      "/usr/bin/python3 " + quoted(checker.string()) + " " + kind + " " + quoted(out.string()) + " " + quoted(dem.string());
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace talus::test
