// The `talus` program: parses the command line and maps failures to the exit codes of
// DESIGN.md section 3 (0 done, 2 bad usage or input, 3 numerical failure, 1 anything else,
// 130 cancelled with Ctrl-C),
// with one line `talus: error: ...` on stderr.
#include <iostream>

#include "commands.hpp"
#include "talus/core/errors.hpp"
#include "talus/core/progress.hpp"

namespace {

int fail(int code, const std::string& message) {
  std::string line = message;
  for (char& c : line) {
    if (c == '\n' || c == '\r') c = ' ';
  }
  std::cerr << "talus: error: " << line << '\n';
  return code;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"Talus: rock-fall and mud-flow hazard maps from a DEM (Gascuel et al. 1998)", "talus"};
  app.set_version_flag("--version", std::string("talus ") + TALUS_VERSION);
  app.require_subcommand(1);
  talus::cli::Action action;
  const std::vector<std::string> command_line(argv, argv + argc);
  talus::cli::add_info_command(app, action);
  talus::cli::add_rockfall_command(app, action, command_line);
  talus::cli::add_mudflow_command(app, action, command_line);
  talus::cli::add_study_command(app, action, command_line);
  talus::cli::add_params_command(app, action);
  talus::cli::add_calibrate_command(app, action, command_line);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(2, std::string(e.what()) + " (see talus --help)");
  }
  try {
    return action();
  } catch (const talus::InputError& e) {
    return fail(2, e.what());
  } catch (const talus::Cancelled& e) {
    return fail(130, e.what());
  } catch (const talus::NumericalFailure& e) {
    return fail(3, e.what());
  } catch (const std::exception& e) {
    return fail(1, e.what());
  }
}
