// The work of `talus study` as one library call (issue 19, item 2; docs/study.md): every scenario
// of a study file run by the subcommands' own calls (rockfall_job.hpp, mudflow_job.hpp) into its
// own folder, with the progress and the time left over the whole study, and study.json.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "job_output.hpp"
#include "process_ranks.hpp"
#include "study_file.hpp"

namespace talus::cli {

struct StudyChoices {
  std::filesystem::path out;
  std::optional<int> threads;            // --threads: every scenario's [run] threads
  std::optional<double> memory;          // --memory: every scenario's [tiles] memory (GB)
  bool project = true;                   // --project: project.qgz, hillshade.tif, quicklook/hazard.png
  std::vector<std::string> command_line;
};

// Checks every scenario's parameters and reads every scenario's inputs first (a bad one is
// InputError with nothing written), then runs the scenarios in the file's order into
// OUT/scenarios/NAME, writes the hazard map, OUT/study.json, the QGIS project (when wanted) and
// OUT/report.md. A scenario that fails stops the study; the
// scenarios finished before it stay committed.
// Among MPI ranks, the ranks share every rock-fall scenario's sources (rockfall_job.hpp), the mud
// flows go to the ranks in turn, and rank 0 writes the study's own files; OUT must be on a file
// system every rank sees.
void study_job(const Study& study, const StudyChoices& choices, const JobOutput& output,
               const ProcessRanks& ranks = single_process());

}  // namespace talus::cli
