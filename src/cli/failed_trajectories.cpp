// Failed rock-fall trajectories in run.json, problem lines and the run's exit code (issue 38,
// item 7; docs/rockfall-full.md, section 5, "Recovery"; docs/layers.md, "run.json").
#include "failed_trajectories.hpp"

#include <algorithm>
#include <cmath>

#include "job_output.hpp"
#include "talus/core/errors.hpp"

namespace talus::cli {
namespace {

// The command line that reruns one trajectory alone: this run's, with --only-source and
// --only-run set to it (docs/rockfall-full.md, section 5).
std::string single_trajectory_command(const std::vector<std::string>& command_line, std::uint64_t source,
                                      std::uint64_t run) {
  std::string text;
  for (std::size_t i = 0; i < command_line.size(); ++i) {
    const std::string& word = command_line[i];
    if (word == "--only-source" || word == "--only-run") {
      ++i;
      continue;
    }
    if (word.rfind("--only-source=", 0) == 0 || word.rfind("--only-run=", 0) == 0) continue;
    const bool plain = !word.empty() && word.find_first_of(" \t'\"$\\") == std::string::npos;
    text += (text.empty() ? "" : " ") + (plain ? word : "'" + word + "'");
  }
  return text + " --only-source " + std::to_string(source) + " --only-run " + std::to_string(run);
}

// "REASON at t = T s, centre (X, Y, Z) m (source S, run K)"; time and place when known.
std::string failure_text(const FailedTrajectory& f) {
  std::string text = f.reason;
  if (std::isfinite(f.time)) {
    text += printf_text(" at t = %.6g s, centre (%.3f, %.3f, %.3f) m", f.time, f.position.x(), f.position.y(),
                        f.position.z());
  }
  return text + printf_text(" (source %llu, run %llu)", static_cast<unsigned long long>(f.source),
                            static_cast<unsigned long long>(f.run));
}

std::uint64_t simulated(const RockfallResult& result) { return result.trajectories + result.failures.size(); }

}  // namespace

double failed_percent(const RockfallResult& result) {
  const std::uint64_t all = simulated(result);
  return all == 0 ? 0.0 : 100.0 * static_cast<double>(result.failures.size()) / static_cast<double>(all);
}

nlohmann::json recovery_record(const RockfallResult& result, double limit_percent) {
  nlohmann::json failures = nlohmann::json::array();
  for (const FailedTrajectory& f : result.failures) {
    const auto number = [](double value) { return std::isfinite(value) ? nlohmann::json(value) : nlohmann::json(nullptr); };
    failures.push_back({{"source", f.source},
                        {"run", f.run},
                        {"time_s", number(f.time)},
                        {"x_m", number(f.position.x())},
                        {"y_m", number(f.position.y())},
                        {"z_m", number(f.position.z())},
                        {"reason", f.reason}});
  }
  return {{"failure_share_percent", limit_percent},
          {"troubled", result.troubled},
          {"redrawn", result.redrawn},
          {"failed", result.failures.size()},
          {"failed_percent", failed_percent(result)},
          {"failures", failures}};
}

std::vector<std::string> failure_problems(const RockfallResult& result, double limit_percent) {
  std::vector<std::string> problems;
  if (result.failures.empty()) return problems;
  const std::size_t listed = std::min(result.failures.size(), kFailureLines);
  for (std::size_t k = 0; k < listed; ++k) {
    const FailedTrajectory& f = result.failures[k];
    problems.push_back("trajectory failed numerically after the recovery: " + failure_text(f) +
                       "; the layers miss it (rerun it alone with --only-source " + std::to_string(f.source) +
                       " --only-run " + std::to_string(f.run) + ")");
  }
  std::string summary =
      printf_text("trajectories: %zu of %llu (%.3g %%) failed numerically and are missing from the layers, within "
                  "[run] failure_share = %g %%; run.json lists them (recovery, failures)",
                  result.failures.size(), static_cast<unsigned long long>(simulated(result)), failed_percent(result),
                  limit_percent);
  if (result.failures.size() > listed) summary += printf_text("; the first %zu are listed above", listed);
  problems.push_back(summary);
  return problems;
}

void check_failure_share(const RockfallResult& result, double limit_percent,
                         const std::vector<std::string>& command_line) {
  if (result.failures.empty() || failed_percent(result) <= limit_percent) return;
  const FailedTrajectory& first = result.failures.front();
  throw NumericalFailure(
      printf_text("%zu of %llu trajectories (%.3g %%) failed numerically, more than [run] failure_share = %g %%; the "
                  "first: ",
                  result.failures.size(), static_cast<unsigned long long>(simulated(result)), failed_percent(result),
                  limit_percent) +
      failure_text(first) + "; nothing was written; to rerun that trajectory alone: " +
      single_trajectory_command(command_line, first.source, first.run));
}

}  // namespace talus::cli
