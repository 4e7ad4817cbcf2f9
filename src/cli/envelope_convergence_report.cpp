// run.json's `runs` and `convergence`, the terminal lines and the convergence problem of a
// rock-fall run (envelope_convergence_report.hpp; docs/layers.md, "run.json").
#include "envelope_convergence_report.hpp"

#include <algorithm>
#include <cstdio>
#include <map>

namespace talus::cli {
namespace {

// "12.3 %" of a fraction.
std::string percent(double fraction) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g %%", 100.0 * fraction);
  return text;
}

// "N of M sources (S %)".
std::string share(std::uint64_t count, std::uint64_t all, const std::string& what) {
  return std::to_string(count) + " of " + std::to_string(all) + " " + what + " (" +
         percent(all > 0 ? static_cast<double>(count) / static_cast<double>(all) : 0.0) + ")";
}

// The runs of the sources that were simulated, sorted.
std::vector<std::uint64_t> simulated_runs(const RockfallResult& result) {
  std::vector<std::uint64_t> runs;
  for (const std::uint64_t n : result.runs_by_source) {
    if (n > 0) runs.push_back(n);
  }
  std::sort(runs.begin(), runs.end());
  return runs;
}

std::string tolerance_text(const RockfallSettings& settings) {
  return "[run] convergence_tolerance = " + percent(settings.convergence.tolerance);
}

// What the whole run's change compares: the two halves of a fixed run, or each source's last doubling.
std::string compared_text(const RockfallSettings& settings) {
  return settings.auto_runs ? "over each source's last doubling of its runs" : "from the first half of the runs to all of them";
}

// "the reach probability changed by R and the energy brought per run by E".
std::string changes_text(const EnvelopeChange& change) {
  return "the reach probability changed by " + percent(change.reach_change) + " and the energy brought per run by " +
         percent(change.energy_change);
}

}  // namespace

nlohmann::ordered_json runs_record(const RockfallResult& result, const RockfallSettings& settings) {
  const std::vector<std::uint64_t> runs = simulated_runs(result);
  nlohmann::ordered_json record = {{"mode", settings.auto_runs ? "auto" : "fixed"}, {"total", result.trajectories}};
  if (runs.empty()) return record;
  record["per_source_min"] = runs.front();
  record["per_source_median"] = runs[runs.size() / 2];
  record["per_source_max"] = runs.back();
  if (!settings.auto_runs) return record;
  if (result.convergence) record["limit"] = result.convergence->run_limit;
  std::map<std::uint64_t, std::uint64_t> histogram;
  for (const std::uint64_t n : runs) ++histogram[n];
  nlohmann::ordered_json sources_by_runs = nlohmann::ordered_json::object();
  for (const auto& [n, count] : histogram) sources_by_runs[std::to_string(n)] = count;
  record["sources_by_runs"] = sources_by_runs;
  record["per_source"] = result.runs_by_source;
  return record;
}

nlohmann::ordered_json convergence_record(const RockfallResult& result, const RockfallSettings& settings) {
  if (!result.convergence) return nullptr;
  const ConvergenceReport& c = *result.convergence;
  nlohmann::ordered_json record = {
      {"criterion", "reach_change = sum |f_half - f_all| / sum f_all and energy_change = sum |g_half - g_all| / sum g_all "
                    "over the cells, f: passages per run, g: kinetic energy (J) per run; converged when both are below "
                    "the tolerance; half: " +
                        std::string(settings.auto_runs ? "each source's runs before its last doubling"
                                                       : "the first half of each source's runs")},
      {"tolerance", settings.convergence.tolerance},
      {"reach_change", c.change.reach_change},
      {"energy_change", c.change.energy_change},
      {"converged", c.converged},
      {"reached_cells_half", c.change.reached_before},
      {"reached_cells_all", c.change.reached_after},
      {"sources", c.sources},
      {"sources_converged", c.sources_converged}};
  if (settings.auto_runs) record["sources_at_limit"] = c.sources_at_limit;
  record["runs_suggested"] = c.converged ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(c.runs_suggested);
  return record;
}

std::vector<std::string> convergence_lines(const RockfallResult& result, const RockfallSettings& settings) {
  std::vector<std::string> lines;
  if (!result.convergence) return lines;
  const ConvergenceReport& c = *result.convergence;
  const std::vector<std::uint64_t> runs = simulated_runs(result);
  if (settings.auto_runs && !runs.empty()) {
    lines.push_back("Runs per source (--runs auto): " + std::to_string(runs.front()) + " to " +
                    std::to_string(runs.back()) + ", median " + std::to_string(runs[runs.size() / 2]) + "; " +
                    share(c.sources_converged, c.sources, "sources") + " converged, " +
                    std::to_string(c.sources_at_limit) + " stopped at the limit of " + std::to_string(c.run_limit) +
                    " runs");
  }
  lines.push_back("Convergence: " + compared_text(settings) + ", " + changes_text(c.change) + ": " +
                  (c.converged ? "converged" : "not converged") + " (" + tolerance_text(settings) + "); " +
                  std::to_string(c.change.reached_after) + " cells reached");
  return lines;
}

std::vector<std::string> convergence_problems(const RockfallResult& result, const RockfallSettings& settings) {
  if (!result.convergence) return {};
  const ConvergenceReport& c = *result.convergence;
  if (c.converged) {
    if (!settings.auto_runs || c.sources_at_limit == 0) return {};
    // The whole map met the tolerance, but these sources' own envelopes did not (issue 38, item 4).
    return {"convergence: " + share(c.sources_at_limit, c.sources, "sources") + " stopped unconverged at the limit of " +
            std::to_string(c.run_limit) + " runs: the maps converged as a whole, but where only these sources reach, "
            "they rest on envelopes that still changed by more than the tolerance in their last doubling (" +
            tolerance_text(settings) + "); raise [run] max_runs to map them as surely as the others"};
  }
  // The envelopes are nested (more runs reach a superset of cells), so the difference is the new cells.
  const std::uint64_t new_cells = c.change.reached_after - c.change.reached_before;
  std::string line = "convergence: the maps have not converged with ";
  line += settings.auto_runs ? "--runs auto" : std::to_string(settings.runs_per_source) + " runs per source";
  line += ": " + compared_text(settings) + ", " + changes_text(c.change) + " (" + tolerance_text(settings) + "); " +
          share(new_cells, c.change.reached_after, "reached cells") + " were reached by the " +
          (settings.auto_runs ? "last doublings" : "second half") + " only; ";
  line += settings.auto_runs ? share(c.sources_at_limit, c.sources, "sources") + " stopped unconverged at the limit of " +
                                   std::to_string(c.run_limit) + " runs"
                             : share(c.sources - c.sources_converged, c.sources, "sources") + " have not converged on their own";
  line += "; about " + std::to_string(c.runs_suggested) +
          " runs per source are needed if the change falls as 1/sqrt(runs): ";
  line += settings.auto_runs ? "raise [run] max_runs to " + std::to_string(c.runs_suggested)
                             : "use --runs " + std::to_string(c.runs_suggested) + ", or --runs auto";
  return {line};
}

}  // namespace talus::cli
