// What a rock-fall run says about the convergence of its envelope (issue 17, items 2 and 5;
// envelope_convergence.hpp; docs/hazard-statistics.md, "Convergence"): run.json's `runs` and
// `convergence`, the terminal's summary lines, and the problem an unconverged envelope is.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/rockfall/monte_carlo.hpp"

namespace talus::cli {

// run.json's `runs`: the mode, the total, the spread over the simulated sources and, in auto
// mode, a histogram and the runs of every source (by source index, 0 where not simulated).
nlohmann::ordered_json runs_record(const RockfallResult& result, const RockfallSettings& settings);

// run.json's `convergence` (null without a test: --only-run).
nlohmann::ordered_json convergence_record(const RockfallResult& result, const RockfallSettings& settings);

// The terminal's lines on the runs per source (auto) and on the convergence, without "problem:".
std::vector<std::string> convergence_lines(const RockfallResult& result, const RockfallSettings& settings);

// One problem line when the whole run's envelope has not converged, in the form of the other
// problems ("convergence: ..."), with its counts and shares and the runs that would converge it;
// with --runs auto, one line too when the whole converged but some sources stopped unconverged
// at the run limit.
std::vector<std::string> convergence_problems(const RockfallResult& result, const RockfallSettings& settings);

}  // namespace talus::cli
