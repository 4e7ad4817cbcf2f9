// Where a job's words go (issue 19: each subcommand's work is one library call, as GDAL's
// utilities are functions with a thin program around them): `talus rockfall` and `talus mudflow`
// print the lines on stdout and the progress on stderr; `talus study` prefixes the lines with the
// scenario and folds the progress into the whole study's.
#pragma once

#include <functional>
#include <string>

#include "talus/core/progress.hpp"

namespace talus::cli {

struct JobOutput {
  std::function<void(const std::string&)> say;  // one line for the user, without its newline
  Progress& progress;
};

// The subcommands' `say`: the line on stdout, flushed, so that it comes before the progress.
void print_line(const std::string& line);

// The subcommands' `say` on this rank (process_ranks.hpp): print_line on rank 0, nothing on the
// others.
std::function<void(const std::string&)> rank_say(bool root);

// printf's formatting into a string, for the lines a job says.
std::string printf_text(const char* format, ...) __attribute__((format(printf, 1, 2)));

}  // namespace talus::cli
