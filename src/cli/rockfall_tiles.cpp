// Rock fall in units of work: tiles, and chunks of sources (rockfall_tiles.hpp; issue 19, items 4 and 5).
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
    whole_.report(before_ + share_ * fraction_done, place_.empty() ? phase : phase + ", " + place_);
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

// The tile's sources in chunks of `size` (by source index); all of them in one when size is 0.
std::vector<std::vector<bool>> chunks_of(const std::vector<bool>& tile, std::size_t size) {
  std::vector<std::vector<bool>> chunks;
  std::size_t in_chunk = 0;
  for (std::size_t s = 0; s < tile.size(); ++s) {
    if (!tile[s]) continue;
    if (chunks.empty() || (size != 0 && in_chunk == size)) {
      chunks.emplace_back(tile.size(), false);
      in_chunk = 0;
    }
    chunks.back()[s] = true;
    ++in_chunk;
  }
  return chunks;
}

}  // namespace

std::optional<RockfallResult> simulate_units(const gis::Scene& region, const GroundModel* whole_ground,
                                             const TilePlan& plan, const std::vector<ReleaseSource>& sources,
                                             const RockfallSettings& settings, const TrajectoryRunner& run,
                                             Progress& progress, const ProcessRanks& ranks, const UnitParts* parts,
                                             TileLines& lines, std::size_t& resumed) {
  const GridSpec& grid = region.dem.elevation.spec();
  const std::vector<std::vector<bool>> selected = sources_by_tile(plan, grid, sources);
  const double total = static_cast<double>(std::max<std::size_t>(1, sources.size()));

  // This rank's share of each unit with sources: (tile, encoded result).
  ByteWriter message;
  std::set<std::string> seen_notes, seen_problems;
  together(ranks, [&] {
    double before = 0;
    for (std::size_t t = 0; t < plan.tiles.size(); ++t) {
      const Tile& tile = plan.tiles[t];
      const std::vector<std::vector<bool>> chunks = chunks_of(selected[t], parts ? kSourcesPerUnit : 0);
      std::optional<GroundModel> tile_ground;  // built when a unit of the tile is to be run
      for (std::size_t c = 0; c < chunks.size(); ++c) {
        const double share = static_cast<double>(std::count(chunks[c].begin(), chunks[c].end(), true)) / total;
        std::optional<std::vector<std::uint8_t>> bytes = parts ? parts->load(t, c) : std::nullopt;
        if (bytes) {
          ++resumed;
        } else {
          if (!whole_ground && !tile_ground) {
            const gis::Scene scene = gis::load_tile(region, tile.window);
            keep_once(lines.notes, seen_notes, scene.notes);
            keep_once(lines.problems, seen_problems, scene.problems);
            tile_ground.emplace(scene.ground_model());
          }
          RockfallSettings unit = settings;
          unit.share.unit = std::make_shared<const std::vector<bool>>(chunks[c]);
          if (plan.tiled()) unit.tile = tile.halo_edge;
          std::string place = plan.tiled() ? "tile " + std::to_string(t + 1) + " of " + std::to_string(plan.tiles.size()) : "";
          if (chunks.size() > 1) place += (place.empty() ? "" : ", ") + std::string("sources ") + std::to_string(c + 1) + " of " + std::to_string(chunks.size());
          TileProgress part(progress, before, share, place);
          bytes = encode_share(run(whole_ground ? *whole_ground : *tile_ground, unit, part));
          if (parts) parts->commit(t, c, *bytes);
        }
        message.put<std::uint64_t>(t);
        message.put_vector(*bytes);
        before += share;
      }
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
                                 std::vector<std::uint64_t>(sources.size(), 0), std::nullopt, std::nullopt, 0, 0, {}});
  }
  return whole;
}

}  // namespace talus::cli
