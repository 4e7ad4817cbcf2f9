// Problem line for a mud flow cut short by the simulated time limit (issue 18, item 4;
// docs/layers.md, "run.json").
#include "unfinished_flow.hpp"

#include <cstdio>

namespace talus::cli {

std::vector<std::string> unfinished_flow_problems(const MudflowResult& result, const MudflowSettings& settings) {
  if (result.end != MudflowEnd::duration || result.history.empty()) return {};
  const MudflowHistoryPoint& last = result.history.back();
  if (last.flowing == 0) return {};
  const double share = result.peak_kinetic_energy > 0.0 ? last.kinetic_energy / result.peak_kinetic_energy : 0.0;
  char line[512];
  std::snprintf(line, sizeof line,
                "mud flow: %zu particles were still flowing at the time limit ([run] duration = %g s), with "
                "%.3g %% of the peak kinetic energy left (the run ends by itself below [run] "
                "stop_energy_fraction = %g %%); the layers miss the rest of the flow: raise [run] duration",
                last.flowing, settings.duration, 100.0 * share, 100.0 * settings.stop_energy_fraction);
  return {line};
}

}  // namespace talus::cli
