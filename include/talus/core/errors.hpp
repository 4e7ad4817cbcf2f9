// Errors the engine and the GIS boundary report, mapped by the CLI to exit codes (docs/architecture.md section 3):
// InputError -> 2 (bad usage or input), NumericalFailure -> 3, anything else -> 1.
#pragma once

#include <stdexcept>
#include <string>

namespace talus {

// Bad user input. The message names the file (or option) and what is wrong, in one line.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Two grids that should share one georeferencing do not.
class GridMismatch : public InputError {
 public:
  using InputError::InputError;
};

// A simulation that became unstable and could not be recovered.
class NumericalFailure : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace talus
