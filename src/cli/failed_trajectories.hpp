// The trajectories a rock-fall run lost to numerical failures that the recovery could not mend
// (issue 38, item 7; docs/rockfall-full.md, section 5, "Recovery"): their record in run.json, one
// problem line each (at most kFailureLines, then a summary), and the run's own failure when
// their share exceeds [run] failure_share.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/rockfall/monte_carlo.hpp"

namespace talus::cli {

// Problem lines that name a failed trajectory each, before the summary line.
inline constexpr std::size_t kFailureLines = 10;

// Failed trajectories over every trajectory simulated (those in the layers and the failed), in %.
double failed_percent(const RockfallResult& result);

// run.json's "recovery": the limit (%), the runs whose first draw met a failed step (troubled),
// those drawn again (redrawn), the failed ones and each failure's source, run, time_s, x_m, y_m,
// z_m and reason.
nlohmann::json recovery_record(const RockfallResult& result, double limit_percent);

// One line per failed trajectory (the first kFailureLines), then a summary; none without failures.
std::vector<std::string> failure_problems(const RockfallResult& result, double limit_percent);

// Throws NumericalFailure (exit code 3, nothing written) when more than limit_percent of the
// trajectories failed, naming the share, the first failure and the command that reruns it alone
// (command_line: the run's, with --only-source and --only-run set to that trajectory).
void check_failure_share(const RockfallResult& result, double limit_percent,
                         const std::vector<std::string>& command_line);

}  // namespace talus::cli
