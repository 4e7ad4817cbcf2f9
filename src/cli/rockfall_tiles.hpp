// A rock fall over a region larger than memory (issue 19, item 4; docs/study.md, "Tiles"): tile
// after tile, the tile's ground is built for its window alone and its sources' trajectories run
// there; each tile's statistics, renumbered onto the region's grid, join exactly as MPI ranks'
// shares do, so that the layers equal an untiled run's bit for bit when no rock reached a halo's
// edge. Under MPI every rank runs its share of every tile's sources.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "process_ranks.hpp"
#include "tile_plan.hpp"
#include "talus/gis/scene.hpp"
#include "talus/rockfall/monte_carlo.hpp"

namespace talus::cli {

// run_rockfall as the job runs it (with its failures' messages).
using TrajectoryRunner =
    std::function<RockfallResult(const GroundModel&, const RockfallSettings&, Progress&)>;

// What the tiles' scenes said about their inputs, each line once.
struct TileLines {
  std::vector<std::string> notes, problems;
};

// The joined result on rank 0 (nothing on the others); every rank runs its share of each tile
// (settings.share's rank and ranks). `region`: the scene of load_region.
std::optional<RockfallResult> simulate_tiles(const gis::Scene& region, const TilePlan& plan,
                                             const std::vector<ReleaseSource>& sources, const RockfallSettings& settings,
                                             const TrajectoryRunner& run, Progress& progress, const ProcessRanks& ranks,
                                             TileLines& lines);

}  // namespace talus::cli
