// Rock fall tile by tile (rockfall_tiles.hpp; issue 19, item 4).
#include "rockfall_tiles.hpp"

#include <algorithm>
#include <memory>
#include <set>

#include "talus/core/byte_stream.hpp"
#include "talus/rockfall/rockfall_shares.hpp"

namespace talus::cli {
namespace {

// One tile's part of the whole run's progress, its place named in the phase.
class TileProgress final : public Progress {
 public:
  TileProgress(Progress& whole, double before, double share, std::string place)
      : whole_(whole), before_(before), share_(share), place_(std::move(place)) {}
  void report(double fraction_done, const std::string& phase) override {
    whole_.report(before_ + share_ * fraction_done, phase + ", " + place_);
  }
  bool cancelled() const override { return whole_.cancelled(); }

 private:
  Progress& whole_;
  double before_, share_;
  std::string place_;
};

void keep_once(std::vector<std::string>& kept, std::set<std::string>& seen, const std::vector<std::string>& lines) {
  for (const auto& line : lines) {
    if (seen.insert(line).second) kept.push_back(line);
  }
}

}  // namespace

std::optional<RockfallResult> simulate_tiles(const gis::Scene& region, const TilePlan& plan,
                                             const std::vector<ReleaseSource>& sources, const RockfallSettings& settings,
                                             const TrajectoryRunner& run, Progress& progress, const ProcessRanks& ranks,
                                             TileLines& lines) {
  const GridSpec& grid = region.dem.elevation.spec();
  const std::vector<std::vector<bool>> selected = sources_by_tile(plan, grid, sources);
  std::vector<std::size_t> counts(plan.tiles.size(), 0);
  for (std::size_t t = 0; t < plan.tiles.size(); ++t) counts[t] = static_cast<std::size_t>(std::count(selected[t].begin(), selected[t].end(), true));
  const double total = static_cast<double>(std::max<std::size_t>(1, sources.size()));

  // This rank's share of each tile with sources: (tile, encoded result).
  ByteWriter message;
  std::set<std::string> seen_notes, seen_problems;
  together(ranks, [&] {
    double before = 0;
    for (std::size_t t = 0; t < plan.tiles.size(); ++t) {
      if (counts[t] == 0) continue;
      const Tile& tile = plan.tiles[t];
      const gis::Scene scene = gis::load_tile(region, tile.window);
      keep_once(lines.notes, seen_notes, scene.notes);
      keep_once(lines.problems, seen_problems, scene.problems);
      const GroundModel ground = scene.ground_model();
      RockfallSettings unit = settings;
      unit.share.unit = std::make_shared<const std::vector<bool>>(selected[t]);
      unit.tile = tile.halo_edge;
      const double share = static_cast<double>(counts[t]) / total;
      TileProgress part(progress, before, share,
                        "tile " + std::to_string(t + 1) + " of " + std::to_string(plan.tiles.size()));
      const RockfallResult result = run(ground, unit, part);
      message.put<std::uint64_t>(t);
      message.put_vector(encode_share(result));
      before += share;
    }
    message.put<std::uint64_t>(plan.tiles.size());  // the end of the message
  });
  const std::vector<std::vector<std::uint8_t>> messages = ranks.gather(message.take());
  if (!ranks.root()) return std::nullopt;

  // Every rank's tiles, each onto the region's grid and joined into the rest at once, so that
  // the statistics of one tile at a time are held beside the whole's.
  std::optional<RockfallResult> whole;
  for (const auto& bytes : messages) {
    ByteReader in(bytes);
    for (std::uint64_t t = in.get<std::uint64_t>(); t < plan.tiles.size(); t = in.get<std::uint64_t>()) {
      std::vector<std::uint8_t> encoded;
      in.get_vector(encoded);
      RockfallResult tile = decode_share(encoded, region.dem.elevation, plan.tiles[t].window);
      if (!whole) {
        whole.emplace(std::move(tile));
        continue;
      }
      std::vector<RockfallResult> pair;
      pair.push_back(std::move(*whole));
      pair.push_back(std::move(tile));
      whole.emplace(join_shares(std::move(pair), settings));
    }
  }
  if (!whole) {  // no source at all: what an untiled run of none gives
    whole.emplace(RockfallResult{RockfallStatistics(region.dem.elevation), {},
                                 std::vector<std::uint64_t>(kStopReasonCount, 0), {}, 0, 1, 0,
                                 std::vector<std::uint64_t>(sources.size(), 0), std::nullopt, std::nullopt});
  }
  return whole;
}

}  // namespace talus::cli
