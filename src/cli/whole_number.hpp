// Whole numbers on the command line (issue 18, item 1): CLI11 reads "-1" into an unsigned
// option as 2^64 - 1 and takes 2^64 as 2^64 - 1; this check refuses both before they wrap.
#pragma once

#include <CLI/CLI.hpp>

namespace talus::cli {

// Digits only, and at most 2^64 - 1: --seed, --only-source, --only-run.
CLI::Validator whole_number();

}  // namespace talus::cli
