// Progress on the terminal: `Progress: N%` lines on stderr (as WhiteboxTools prints them), and
// Ctrl-C turned into a clean cancel (nothing is written).
#pragma once

#include "talus/core/progress.hpp"

namespace talus::cli {

class TerminalProgress final : public Progress {
 public:
  // Installs the SIGINT handler; `shown` false: prints nothing (MPI ranks other than 0).
  explicit TerminalProgress(bool shown = true);
  ~TerminalProgress() override;
  void report(double fraction_done, const std::string& phase) override;
  bool cancelled() const override;

 private:
  bool shown_;
  int last_percent_ = -1;
};

}  // namespace talus::cli
