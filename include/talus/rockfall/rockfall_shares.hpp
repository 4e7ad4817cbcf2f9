// A rock-fall run split among processes (issue 19, item 6): each MPI rank simulates its
// SourceShare of the sources (monte_carlo.hpp) with the same counter-based random numbers as the
// whole run, sends its result to rank 0 as bytes, and rank 0 joins the shares. Every statistic
// merges exactly (rockfall_statistics.hpp), so the joined result, and every layer made from it,
// is bit-identical to the whole run in one process, for any number of ranks.
#pragma once

#include <cstdint>
#include <vector>

#include "talus/core/grid.hpp"
#include "talus/rockfall/monte_carlo.hpp"

namespace talus {

// One share's result as bytes (core/byte_stream.hpp).
std::vector<std::uint8_t> encode_share(const RockfallResult& share);

// The bytes of encode_share, for a run on `dem` (the statistics' grid). A tile's share (issue 19,
// item 4), simulated on the window `tile` of `dem`'s grid, is decoded onto the whole of `dem`.
RockfallResult decode_share(const std::vector<std::uint8_t>& bytes, const Grid<double>& dem,
                            const GridSpec& tile = GridSpec{});

// The whole run's result from shares that split its sources between them, each source's runs in
// one share: MPI ranks' (shares[r] simulated with settings.share = {r, shares.size()}) or tiles'
// (decoded onto the whole grid), as run_rockfall returns it for settings.share = {0, 1}. The
// result's `threads` is the first share's.
RockfallResult join_shares(std::vector<RockfallResult> shares, const RockfallSettings& settings);

}  // namespace talus
