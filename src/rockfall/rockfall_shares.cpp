// Encoding, decoding and joining the shares of a rock-fall run split among MPI ranks
// (rockfall_shares.hpp; issue 19, item 6).
#include "talus/rockfall/rockfall_shares.hpp"

#include <algorithm>
#include <stdexcept>

#include "talus/core/byte_stream.hpp"

namespace talus {
namespace {

void write_line(ByteWriter& out, const TrajectoryLine& line) {
  out.put(line.source_id);
  out.put(line.run_id);
  out.put(line.release_fid);
  out.put(line.stop_reason);
  out.put(line.max_energy);
  out.put(line.runout_length);
  out.put<std::uint64_t>(line.vertices.size());
  for (const TrajectoryVertex& v : line.vertices) {
    out.put(v.position.x());
    out.put(v.position.y());
    out.put(v.position.z());
    out.put(v.time);
    out.put(v.speed);
    out.put(v.kinetic_energy);
    out.put(v.jump_height);
  }
}

TrajectoryLine read_line(ByteReader& in) {
  TrajectoryLine line;
  line.source_id = in.get<std::uint64_t>();
  line.run_id = in.get<std::uint64_t>();
  line.release_fid = in.get<std::int64_t>();
  line.stop_reason = in.get<StopReason>();
  line.max_energy = in.get<double>();
  line.runout_length = in.get<double>();
  line.vertices.resize(in.get<std::uint64_t>());
  for (TrajectoryVertex& v : line.vertices) {
    v.position.x() = in.get<double>();
    v.position.y() = in.get<double>();
    v.position.z() = in.get<double>();
    v.time = in.get<double>();
    v.speed = in.get<double>();
    v.kinetic_energy = in.get<double>();
    v.jump_height = in.get<double>();
  }
  return line;
}

void write_failure(ByteWriter& out, const FailedTrajectory& failure) {
  out.put(failure.source);
  out.put(failure.run);
  out.put(failure.time);
  out.put(failure.position.x());
  out.put(failure.position.y());
  out.put(failure.position.z());
  out.put<std::uint64_t>(failure.reason.size());
  for (const char c : failure.reason) out.put(c);
}

FailedTrajectory read_failure(ByteReader& in) {
  FailedTrajectory failure;
  failure.source = in.get<std::uint64_t>();
  failure.run = in.get<std::uint64_t>();
  failure.time = in.get<double>();
  failure.position.x() = in.get<double>();
  failure.position.y() = in.get<double>();
  failure.position.z() = in.get<double>();
  failure.reason.resize(in.get<std::uint64_t>());
  for (char& c : failure.reason) c = in.get<char>();
  return failure;
}

}  // namespace

std::vector<std::uint8_t> encode_share(const RockfallResult& share) {
  ByteWriter out;
  share.statistics.write(out);
  out.put<std::uint64_t>(share.lines.size());
  for (const TrajectoryLine& line : share.lines) write_line(out, line);
  out.put_vector(share.stop_counts);
  out.put_vector(share.runouts);
  out.put(share.trajectories);
  out.put(share.threads);
  out.put(share.fragments);
  out.put_vector(share.runs_by_source);
  out.put<std::uint8_t>(share.convergence_sums ? 1 : 0);
  if (const auto& sums = share.convergence_sums) {
    sums->half.write(out);
    sums->all.write(out);
    out.put(sums->sources);
    out.put(sums->sources_converged);
    out.put(sums->sources_at_limit);
  }
  out.put(share.troubled);
  out.put(share.redrawn);
  out.put<std::uint64_t>(share.failures.size());
  for (const FailedTrajectory& failure : share.failures) write_failure(out, failure);
  return out.take();
}

RockfallResult decode_share(const std::vector<std::uint8_t>& bytes, const Grid<double>& dem, const GridSpec& tile) {
  if (tile.is_window() && !tile.whole().same_grid(dem.spec())) throw std::invalid_argument("decode_share: a tile of another grid");
  ByteReader in(bytes, tile);
  RockfallResult share{RockfallStatistics(dem), {}, {}, {}, 0, 1, 0, {}, std::nullopt, std::nullopt, 0, 0, {}};
  share.statistics.read(in);
  share.lines.resize(in.get<std::uint64_t>());
  for (TrajectoryLine& line : share.lines) line = read_line(in);
  in.get_vector(share.stop_counts);
  in.get_vector(share.runouts);
  share.trajectories = in.get<std::uint64_t>();
  share.threads = in.get<int>();
  share.fragments = in.get<std::uint64_t>();
  in.get_vector(share.runs_by_source);
  if (in.get<std::uint8_t>() != 0) {
    ConvergenceSums& sums = share.convergence_sums.emplace(dem.size());
    sums.half.read(in);
    sums.all.read(in);
    sums.sources = in.get<std::uint64_t>();
    sums.sources_converged = in.get<std::uint64_t>();
    sums.sources_at_limit = in.get<std::uint64_t>();
  }
  share.troubled = in.get<std::uint64_t>();
  share.redrawn = in.get<std::uint64_t>();
  share.failures.resize(in.get<std::uint64_t>());
  for (FailedTrajectory& failure : share.failures) failure = read_failure(in);
  if (!in.at_end()) throw std::runtime_error("rank message: longer than its contents");
  return share;
}

RockfallResult join_shares(std::vector<RockfallResult> shares, const RockfallSettings& settings) {
  if (shares.empty()) throw std::invalid_argument("join_shares: no shares");
  const std::size_t source_count = shares.front().runs_by_source.size();
  // runouts: each share's in (source, run) order; the whole run's interleaves them source by
  // source, taking each source's runs from the share that simulated it (a source belongs to one
  // share, whether the shares are MPI ranks' or tiles', and every simulated source has runs),
  // less its failed runs, which have no runout.
  std::vector<std::size_t> next_runout(shares.size(), 0);
  std::vector<double> runouts;
  std::vector<std::uint64_t> failed_runs(source_count, 0);
  for (const RockfallResult& share : shares) {
    for (const FailedTrajectory& failure : share.failures) {
      if (failure.source < source_count) ++failed_runs[failure.source];
    }
  }

  for (std::uint64_t source = 0; source < source_count; ++source) {
    std::size_t owner = 0;
    while (owner < shares.size() && shares[owner].runs_by_source[source] == 0) ++owner;
    if (owner == shares.size()) continue;
    const std::vector<double>& from = shares[owner].runouts;
    const std::size_t begin = next_runout[owner];
    next_runout[owner] += shares[owner].runs_by_source[source] - failed_runs[source];
    if (next_runout[owner] > from.size()) throw std::runtime_error("join_shares: a share lacks runs it owns");
    runouts.insert(runouts.end(), from.begin() + static_cast<std::ptrdiff_t>(begin),
                   from.begin() + static_cast<std::ptrdiff_t>(next_runout[owner]));
  }
  RockfallResult whole = std::move(shares.front());
  for (std::size_t r = 1; r < shares.size(); ++r) {
    RockfallResult& share = shares[r];
    whole.statistics.merge(share.statistics);
    for (auto& line : share.lines) whole.lines.push_back(std::move(line));
    for (std::size_t k = 0; k < whole.stop_counts.size(); ++k) whole.stop_counts[k] += share.stop_counts[k];
    whole.trajectories += share.trajectories;
    whole.fragments += share.fragments;
    whole.troubled += share.troubled;
    whole.redrawn += share.redrawn;
    for (auto& failure : share.failures) whole.failures.push_back(std::move(failure));
    for (std::size_t s = 0; s < source_count; ++s) whole.runs_by_source[s] += share.runs_by_source[s];
    if (whole.convergence_sums && share.convergence_sums) {
      ConvergenceSums& sums = *whole.convergence_sums;
      sums.half.merge(share.convergence_sums->half);
      sums.all.merge(share.convergence_sums->all);
      sums.sources += share.convergence_sums->sources;
      sums.sources_converged += share.convergence_sums->sources_converged;
      sums.sources_at_limit += share.convergence_sums->sources_at_limit;
    }
  }
  whole.runouts = std::move(runouts);
  std::sort(whole.lines.begin(), whole.lines.end(), [](const TrajectoryLine& a, const TrajectoryLine& b) {
    return a.source_id != b.source_id ? a.source_id < b.source_id : a.run_id < b.run_id;
  });
  std::sort(whole.failures.begin(), whole.failures.end());
  if (whole.convergence_sums) whole.convergence = convergence_report(*whole.convergence_sums, settings);
  return whole;
}

}  // namespace talus
