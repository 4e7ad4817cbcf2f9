// Problem lines for rock-fall trajectories cut short by the nodata edge, the DEM's edge or the
// time limit (issue 17, item 5; docs/layers.md, "run.json").
#include "truncated_trajectories.hpp"

#include <cstdio>
#include <numeric>

#include "talus/rockfall/trajectory_observer.hpp"

namespace talus::cli {

std::vector<std::string> truncated_trajectory_problems(const std::vector<std::uint64_t>& stop_counts,
                                                       const std::string& max_time_key, double max_time_s,
                                                       double halo_m) {
  const std::uint64_t rocks = std::accumulate(stop_counts.begin(), stop_counts.end(), std::uint64_t{0});
  char limit[64];
  std::snprintf(limit, sizeof limit, "%g s", max_time_s);
  char halo[64];
  std::snprintf(halo, sizeof halo, "%g m", halo_m);
  const struct {
    StopReason reason;
    std::string what;
  } causes[] = {
      {StopReason::nodata_area, "stopped where they entered cells without elevation (the DEM's nodata edge); "
                                "the layers end there, so the area beyond may be reached too"},
      {StopReason::left_dem, "left the DEM's extent; the layers end at its edge, so the area beyond may be reached too"},
      {StopReason::max_time, "were still moving at the time limit (" + max_time_key + " = " + limit +
                                 "); the layers miss the rest of their paths: raise " + max_time_key},
      {StopReason::tile_edge, "reached the edge of their tile's halo ([tiles] halo = " + std::string(halo) +
                                  ") and were stopped there; the layers miss the rest of their paths: raise --halo"},
  };
  std::vector<std::string> problems;
  for (const auto& cause : causes) {
    const auto index = static_cast<std::size_t>(cause.reason);
    const std::uint64_t count = index < stop_counts.size() ? stop_counts[index] : 0;
    if (count == 0) continue;
    char share[96];
    const double percent = 100.0 * static_cast<double>(count) / static_cast<double>(rocks);
    std::snprintf(share, sizeof share, "%llu of %llu rocks (%.3g %%) ", static_cast<unsigned long long>(count),
                  static_cast<unsigned long long>(rocks), percent);
    problems.push_back("trajectories: " + std::string(share) + cause.what + " (stop reason " + to_string(cause.reason) +
                       ")");
  }
  return problems;
}

}  // namespace talus::cli
