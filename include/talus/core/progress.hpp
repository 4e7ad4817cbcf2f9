// Progress and cancellation of long runs (GDAL's progress-callback idea): the engine reports
// the fraction done and asks whether to stop; the CLI prints `Progress: N%` lines and turns
// Ctrl-C into a cancel. Engines call these from one thread at a time.
#pragma once

#include <string>

namespace talus {

class Progress {
 public:
  virtual ~Progress() = default;
  virtual void report(double fraction_done, const std::string& phase) = 0;  // 0..1
  virtual bool cancelled() const = 0;
};

// Thrown by an engine that saw Progress::cancelled(); nothing is written after it.
class Cancelled : public std::exception {
 public:
  const char* what() const noexcept override { return "cancelled by the user"; }
};

}  // namespace talus
