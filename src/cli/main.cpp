// The `talus` program: parses the command line and maps failures to the exit codes of
// docs/architecture.md section 3 (0 done, 2 bad usage or input, 3 numerical failure, 1 anything else,
// 130 cancelled with Ctrl-C),
// with one line `talus: error: ...` on stderr (from rank 0 alone when mpirun or srun started it:
// process_ranks.hpp).
#include <iostream>
#include <memory>

#include "commands.hpp"
#include "talus/core/errors.hpp"
#include "talus/core/progress.hpp"
#include "talus/gis/build_commit.hpp"
#ifdef TALUS_WITH_MPI
#include "mpi_ranks.hpp"
#endif

namespace {

bool error_shown = true;  // false on MPI ranks other than 0

int fail(int code, const std::string& message) {
  if (!error_shown) return code;
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
  app.set_version_flag("--version", std::string("talus ") + TALUS_VERSION + " (commit " +
                                        std::string(talus::gis::git_commit()) + ")");
  app.require_subcommand(1);
  talus::cli::Action action;
  const std::vector<std::string> command_line(argv, argv + argc);
  std::unique_ptr<talus::cli::ProcessRanks> mpi;
#ifdef TALUS_WITH_MPI
  if (talus::cli::started_by_mpi_launcher()) mpi = talus::cli::mpi_ranks(argc, argv);
#endif
  const talus::cli::ProcessRanks& ranks = mpi ? *mpi : talus::cli::single_process();
  error_shown = ranks.root();
  talus::cli::add_info_command(app, action);
  talus::cli::add_rockfall_command(app, action, command_line, ranks);
  talus::cli::add_mudflow_command(app, action, command_line);
  talus::cli::add_study_command(app, action, command_line, ranks);
  talus::cli::add_params_command(app, action);
  talus::cli::add_calibrate_command(app, action, command_line);
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return fail(2, std::string(e.what()) + " (see talus --help)");
  }
  const std::string command = app.get_subcommands().front()->get_name();
  if (ranks.size() > 1 && command != "rockfall" && command != "study") {
    return fail(2, "talus " + command + " runs in one process; under mpirun or srun run talus rockfall or talus study, "
                   "whose ranks share the rock-fall sources");
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
