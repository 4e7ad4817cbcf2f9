// Tests of a rock-fall run split among MPI ranks (rockfall_shares.hpp; issue 19, item 6): the
// shares, each sent through its bytes and joined, give the whole run's result bit for bit, for
// fixed and automatic runs, saved lines and one source alone, whatever the number of ranks.
#include "talus/rockfall/rockfall_shares.hpp"

#include <algorithm>
#include <cstring>
#include <memory>

#include <gtest/gtest.h>

#include "../../validation/synthetic_ground.hpp"
#include "talus/rockfall/fast_bounce.hpp"

namespace talus {
namespace {

// A 100 m slope falling towards +x at 80 % onto a flat floor, with 0.3 m of noise, and 40 point
// sources along its top: more than two blocks of SourceShare::block, so that three ranks each get
// a different number of sources.
class RockfallShares : public ::testing::Test {
 protected:
  RockfallShares()
      : ground_(testing_ground::make_ground(testing_ground::local_spec(40, 30, 5.0),
                                            [](double x, double) { return 200.0 - 0.8 * std::min(x, 100.0); },
                                            testing_ground::fast_material(0.3, 0.6, 0.35, 0.0, 0.3))) {
    for (int k = 0; k < 40; ++k) sources_.push_back({15.0 + 0.5 * (k % 3), -10.0 - 3.5 * k, false, {}});
    settings_.runs_per_source = 12;
    settings_.saved_trajectories = 70;
    settings_.threads = 2;
    settings_.convergence = {0.1, 8, 64};
  }

  RockfallResult run(const RockfallSettings& settings) const {
    return run_rockfall(ground_, sources_, FastBounce(), settings, nullptr);
  }

  // The run split into `ranks` shares, each through its bytes, joined.
  RockfallResult split(RockfallSettings settings, std::uint32_t ranks) const {
    std::vector<RockfallResult> shares;
    for (std::uint32_t r = 0; r < ranks; ++r) {
      settings.share = {r, ranks, nullptr};
      shares.push_back(decode_share(encode_share(run(settings)), ground_.elevation_grid()));
    }
    return join_shares(std::move(shares), settings);
  }

  static bool same(const Grid<float>& a, const Grid<float>& b) {
    return a.size() == b.size() && std::memcmp(a.values().data(), b.values().data(), a.size() * sizeof(float)) == 0;
  }

  static void expect_same(const RockfallResult& a, const RockfallResult& b) {
    const RockfallLayers la = a.statistics.layers(), lb = b.statistics.layers();
    for (const auto member : {&RockfallLayers::reach_probability, &RockfallLayers::passages, &RockfallLayers::source_count,
                              &RockfallLayers::deposits, &RockfallLayers::energy_max, &RockfallLayers::energy_p95,
                              &RockfallLayers::jump_height_p95, &RockfallLayers::velocity_max,
                              &RockfallLayers::energy_loss_friction, &RockfallLayers::energy_loss_deformation}) {
      EXPECT_TRUE(same(la.*member, lb.*member));
    }
    EXPECT_EQ(a.statistics.rocks(), b.statistics.rocks());
    EXPECT_EQ(a.trajectories, b.trajectories);
    EXPECT_EQ(a.fragments, b.fragments);
    EXPECT_EQ(a.stop_counts, b.stop_counts);
    EXPECT_EQ(a.runouts, b.runouts);
    EXPECT_EQ(a.runs_by_source, b.runs_by_source);
    ASSERT_EQ(a.lines.size(), b.lines.size());
    for (std::size_t k = 0; k < a.lines.size(); ++k) {
      EXPECT_EQ(a.lines[k].source_id, b.lines[k].source_id);
      EXPECT_EQ(a.lines[k].run_id, b.lines[k].run_id);
      EXPECT_EQ(a.lines[k].max_energy, b.lines[k].max_energy);
      ASSERT_EQ(a.lines[k].vertices.size(), b.lines[k].vertices.size());
      for (std::size_t v = 0; v < a.lines[k].vertices.size(); ++v) {
        EXPECT_EQ(a.lines[k].vertices[v].position, b.lines[k].vertices[v].position);
      }
    }
    ASSERT_EQ(a.convergence.has_value(), b.convergence.has_value());
    if (a.convergence) {
      EXPECT_EQ(a.convergence->change.reach_change, b.convergence->change.reach_change);
      EXPECT_EQ(a.convergence->change.energy_change, b.convergence->change.energy_change);
      EXPECT_EQ(a.convergence->sources, b.convergence->sources);
      EXPECT_EQ(a.convergence->sources_converged, b.convergence->sources_converged);
      EXPECT_EQ(a.convergence->runs_suggested, b.convergence->runs_suggested);
    }
  }

  GroundModel ground_;
  std::vector<ReleaseSource> sources_;
  RockfallSettings settings_;
};

TEST_F(RockfallShares, SharesJoinToTheWholeRunForAnyNumberOfRanks) {
  const RockfallResult whole = run(settings_);
  ASSERT_GT(whole.lines.size(), 10u);
  for (const std::uint32_t ranks : {1u, 2u, 3u, 5u}) {
    SCOPED_TRACE(ranks);
    expect_same(split(settings_, ranks), whole);
  }
}

TEST_F(RockfallShares, AutomaticRunsJoinToTheWholeRun) {
  RockfallSettings automatic = settings_;
  automatic.auto_runs = true;
  const RockfallResult whole = run(automatic);
  expect_same(split(automatic, 3), whole);
}

TEST_F(RockfallShares, OneSourceOrOneRunJoinsToTheWholeRun) {
  RockfallSettings one_source = settings_, one_run = settings_;
  one_source.only_source = 17;
  one_run.only_run = 4;
  expect_same(split(one_source, 2), run(one_source));
  expect_same(split(one_run, 2), run(one_run));
}

TEST_F(RockfallShares, AShareSimulatesOnlyItsBlocksOfSources) {
  RockfallSettings settings = settings_;
  settings.share = {1, 2, nullptr};
  const RockfallResult share = run(settings);
  for (std::size_t s = 0; s < sources_.size(); ++s) {
    EXPECT_EQ(share.runs_by_source[s], (s / SourceShare::block) % 2 == 1 ? 12u : 0u) << "source " << s;
  }
}

// Issue 19, item 4: two tiles, the sources of rows 0-14 and of rows 15-29, each run on its window
// of the ground with a halo of 5 rows, decoded onto the whole grid and joined, give the whole
// run's result bit for bit (the rocks run down the slope, along x, and stay within the halo);
// a narrower halo stops rocks at its edge.
TEST_F(RockfallShares, TilesOnTheirWindowsJoinToTheWholeRun) {
  const GridSpec& grid = ground_.spec();
  const auto tile_run = [&](int first_row, int rows, int halo_rows, int margin_rows, bool automatic) {
    const int r0 = std::max(0, first_row - halo_rows - margin_rows);
    const int r1 = std::min(grid.height, first_row + rows + halo_rows + margin_rows);
    const GridSpec window = grid.window(0, r0, grid.width, r1 - r0);
    const GroundModel tile_ground(window_of(ground_.elevation_grid(), window), window_of(ground_.material_grid(), window));
    RockfallSettings settings = settings_;
    settings.auto_runs = automatic;
    auto in_tile = std::make_shared<std::vector<bool>>(sources_.size());
    for (std::size_t s = 0; s < sources_.size(); ++s) {
      const double row = grid.row_of(sources_[s].y);
      (*in_tile)[s] = row >= first_row - 0.5 && row < first_row + rows - 0.5;
    }
    settings.share.unit = in_tile;
    TileBounds bounds;
    if (first_row - halo_rows > 0) bounds.y_max = grid.geotransform[3] + (first_row - halo_rows) * grid.geotransform[5];
    if (first_row + rows + halo_rows < grid.height) {
      bounds.y_min = grid.geotransform[3] + (first_row + rows + halo_rows) * grid.geotransform[5];
    }
    settings.tile = bounds;
    const RockfallResult result = run_rockfall(tile_ground, sources_, FastBounce(), settings, nullptr);
    return decode_share(encode_share(result), ground_.elevation_grid(), window);
  };
  for (const bool automatic : {false, true}) {
    SCOPED_TRACE(automatic);
    RockfallSettings settings = settings_;
    settings.auto_runs = automatic;
    std::vector<RockfallResult> tiles;
    tiles.push_back(tile_run(0, 15, 5, 3, automatic));
    tiles.push_back(tile_run(15, 15, 5, 3, automatic));
    const std::size_t stopped = static_cast<std::size_t>(StopReason::tile_edge);
    ASSERT_EQ(tiles[0].stop_counts[stopped] + tiles[1].stop_counts[stopped], 0u);
    expect_same(join_shares(std::move(tiles), settings), run(settings));
  }
  const RockfallResult narrow = tile_run(0, 15, 0, 3, false);
  EXPECT_GT(narrow.stop_counts[static_cast<std::size_t>(StopReason::tile_edge)], 0u);
}

TEST_F(RockfallShares, ATruncatedMessageIsRefused) {
  std::vector<std::uint8_t> bytes = encode_share(run(settings_));
  bytes.resize(bytes.size() / 2);
  EXPECT_THROW(decode_share(bytes, ground_.elevation_grid()), std::runtime_error);
}

}  // namespace
}  // namespace talus
