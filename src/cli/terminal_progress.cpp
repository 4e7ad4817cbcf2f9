#include "terminal_progress.hpp"

#include <atomic>
#include <csignal>
#include <cstdio>

namespace talus::cli {
namespace {

std::atomic<bool> interrupted{false};

extern "C" void on_interrupt(int) { interrupted.store(true); }

}  // namespace

TerminalProgress::TerminalProgress(bool shown) : shown_(shown) {
  interrupted.store(false);
  std::signal(SIGINT, on_interrupt);
}

TerminalProgress::~TerminalProgress() { std::signal(SIGINT, SIG_DFL); }

void TerminalProgress::report(double fraction_done, const std::string& phase) {
  if (!shown_) return;
  const int percent = static_cast<int>(fraction_done * 100.0);
  if (percent / 10 == last_percent_ / 10 && percent != 100) return;  // a line every 10 %
  if (percent == last_percent_) return;
  last_percent_ = percent;
  std::fprintf(stderr, "Progress: %d%% (%s)\n", percent, phase.c_str());
}

bool TerminalProgress::cancelled() const { return interrupted.load(); }

}  // namespace talus::cli
