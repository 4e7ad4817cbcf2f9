// A rock fall in units of work (issue 19, items 4 and 5; docs/study.md, "Tiles" and "Resume"):
// over a region larger than memory, tile after tile, the tile's ground is built for its window
// alone and its sources' trajectories run there; in a study, the sources also go in chunks, each
// committed as it finishes. Each unit's statistics, renumbered onto the region's grid, join
// exactly as MPI ranks' shares do, so that the layers equal an untiled run's bit for bit when no
// rock reached a halo's edge. Under MPI every rank runs its share of every unit's sources.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "process_ranks.hpp"
#include "tile_plan.hpp"
#include "unit_parts.hpp"
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

// Sources per unit of work when units are committed (UnitParts): small enough that a kill loses
// little, large enough that a unit's threads rarely wait for its slowest source.
inline constexpr std::size_t kSourcesPerUnit = 256;

// The joined result on rank 0 (nothing on the others): every rank runs its share (settings.share's
// rank and ranks) of each unit of work, a tile's sources, or with `parts` a tile's chunks of
// kSourcesPerUnit sources each committed there as it finishes and taken from there when a
// killed run left it (`resumed` counts those). `region`: the scene of load_region; `whole_ground`:
// its ground model when the plan is not tiled.
std::optional<RockfallResult> simulate_units(const gis::Scene& region, const GroundModel* whole_ground,
                                             const TilePlan& plan, const std::vector<ReleaseSource>& sources,
                                             const RockfallSettings& settings, const TrajectoryRunner& run,
                                             Progress& progress, const ProcessRanks& ranks, const UnitParts* parts,
                                             TileLines& lines, std::size_t& resumed);

}  // namespace talus::cli
