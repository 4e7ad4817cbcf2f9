// Progress on the terminal: `Progress: N%` lines on stderr (as WhiteboxTools prints them), and
// Ctrl-C turned into a clean cancel (nothing is written).
#pragma once

#include "talus/core/progress.hpp"

namespace talus::cli {

class TerminalProgress final : public Progress {
 public:
  TerminalProgress();   // installs the SIGINT handler
  ~TerminalProgress() override;
  void report(double fraction_done, const std::string& phase) override;
  bool cancelled() const override;

 private:
  int last_percent_ = -1;
};

}  // namespace talus::cli
