// `talus study` (issue 19, item 2; docs/study.md): a study file's scenarios, each run as its
// subcommand would run it, with the lines on stdout and the study's progress on stderr.
#include <memory>

#include "commands.hpp"
#include "job_output.hpp"
#include "parameter_table.hpp"
#include "run_project.hpp"
#include "study_file.hpp"
#include "study_job.hpp"
#include "terminal_progress.hpp"
#include "talus/core/errors.hpp"

namespace talus::cli {

void add_study_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line,
                       const ProcessRanks& ranks) {
  struct Options {
    std::filesystem::path file;
    StudyChoices choices;
    int threads = 0;
    double memory = 0;
    std::string project = "on";
  };
  auto o = std::make_shared<Options>();
  o->choices.command_line = command_line;
  CLI::App* cmd = app.add_subcommand("study", "Every rock-fall and mud-flow scenario of a study file (docs/study.md)");
  cmd->add_option("file", o->file, "Study file (TOML): the region's inputs and its scenarios")->required();
  cmd->add_option("--out", o->choices.out, "Output folder: scenarios/NAME per scenario, study.json")->required();
  auto* threads = cmd->add_option("--threads", o->threads, "Threads of every scenario (default: its [run] threads, all cores)");
  auto* memory = cmd->add_option("--memory", o->memory,
                                 "GB each scenario may use; a larger region runs in tiles (docs/study.md, Tiles)");
  cmd->add_option("--project", o->project,
                  "on (default): also write project.qgz, hillshade.tif and quicklook/hazard.png with QGIS; off");
  cmd->callback([o, &action, &ranks, threads, memory] {
    action = [o, &ranks, threads, memory] {
      o->choices.project = project_wanted(o->project);
      if (threads->count() > 0) {
        if (o->threads < 0 || o->threads > kMaxThreads) {
          throw InputError("--threads " + std::to_string(o->threads) + ": expected 0 (all cores) to " +
                           std::to_string(static_cast<int>(kMaxThreads)));
        }
        o->choices.threads = o->threads;
      }
      if (memory->count() > 0) o->choices.memory = o->memory;  // range-checked with each scenario's [tiles]
      const Study study = read_study(o->file);
      TerminalProgress progress(ranks.root());
      study_job(study, o->choices, JobOutput{rank_say(ranks.root()), progress}, ranks);
      return 0;
    };
  });
}

}  // namespace talus::cli
