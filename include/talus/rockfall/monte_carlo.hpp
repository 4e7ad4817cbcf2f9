// The stochastic simulation of paper 3.4: every release source runs N times (or, in auto mode, as
// many times as its envelope needs to converge: envelope_convergence.hpp), each run on its own
// Perlin-perturbed ground with its own release point inside the source cell, rock size, density
// and material parameters. Random numbers are counter-based from (seed, source, run), so run k of
// source s is the same trajectory however many runs the source gets, and statistics merge
// exactly, so the layers are bit-identical for any thread count.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "talus/core/errors.hpp"
#include "talus/core/progress.hpp"
#include "talus/core/release.hpp"
#include "talus/core/tile_bounds.hpp"
#include "talus/ground/ground_model.hpp"
#include "talus/rockfall/envelope_convergence.hpp"
#include "talus/rockfall/rock.hpp"
#include "talus/rockfall/rockfall_statistics.hpp"
#include "talus/rockfall/trajectory_line.hpp"
#include "talus/rockfall/trajectory_model.hpp"

namespace talus {

// How much each run varies around the nominal rock and materials (paper 3.4).
struct StochasticParameters {
  double release_jitter = 1.0;          // - : release point uniform over this fraction of its cell
  double release_height = 0.5;          // m : start height of the rock's lowest point above the ground
  double size_variation = 0.1;          // - : axes scaled by U(1 - v, 1 + v)
  double density_variation = 0.05;      // - : density scaled by U(1 - v, 1 + v)
  double restitution_variation = 0.1;   // - : restitutions scaled by U(1 - v, 1 + v)
  double friction_variation = 0.1;      // - : friction scaled by U(1 - v, 1 + v)
  double noise_frequency = 1.0;         // - : Perlin base frequency lambda = this / rock diameter
  int noise_octaves = 3;                // Perlin octaves
  double noise_reference_size = 1.0;    // m : rocks at least this large see the table's noise amplitudes;
                                        //     a smaller rock of size D sees them scaled by D / this
};

// The share of a run's sources that one process simulates, for MPI (issue 19, item 6): of the
// sources selected, in their order, blocks of `block` consecutive ones are dealt to the ranks in
// turn, so that neighbouring sources (of similar cost) spread over the ranks.
struct SourceShare {
  std::uint32_t rank = 0;
  std::uint32_t ranks = 1;
  static constexpr std::size_t block = 16;
  // A unit of work of a tiled run (issue 19, items 4 and 5; docs/study.md, "Tiles"): only the
  // sources it selects; none: every source.
  std::shared_ptr<const std::vector<bool>> unit;
  bool owns(std::size_t position, std::uint64_t source) const {
    return (position / block) % ranks == rank && (!unit || (*unit)[source]);
  }
};



struct RockfallSettings {
  Rock rock;                            // the nominal rock
  StochasticParameters stochastic;
  std::uint64_t runs_per_source = 10;   // trajectories per release cell or point (unless auto_runs)
  bool auto_runs = false;               // runs per source chosen by the convergence of its envelope
  ConvergenceParameters convergence;    // the convergence test (every run) and auto's batches
  std::uint64_t seed = 1;
  int threads = 0;                      // 0: OpenMP's default
  std::size_t saved_trajectories = 500; // at most this many lines kept for trajectories.gpkg
  // Only the runs of this source, and only this run of each source (0-based, as the lines'
  // source_id and run_id): one trajectory drawn exactly as in the whole run, to reproduce it.
  // With auto_runs, only_source runs that source's batches as the whole run does; only_run
  // simulates that one run of each source, without batches or a convergence test.
  std::optional<std::uint64_t> only_source, only_run;
  SourceShare share;                    // the whole run unless split among MPI ranks or tiles
  std::optional<TileBounds> tile;       // a tile's run: its halo's edge; a trajectory with a
                                        // sample beyond it stops there (StopReason::tile_edge)
  int redraws = 2;                      // a run that failed numerically is drawn again from a fresh
                                        // stream (CounterRandom's `draw`) up to this many times, then
                                        // recorded as failed (docs/rockfall-full.md, section 5, "Recovery")
};

// A run that failed numerically on every draw (docs/rockfall-full.md, section 5, "Recovery"): it
// adds nothing to the statistics, the lines or the runouts. Its source and run (0-based) rerun it
// through RockfallSettings::only_source and only_run; time, place and reason are its last draw's.
struct FailedTrajectory {
  std::uint64_t source = 0, run = 0;
  double time = 0;                                     // s since release
  Eigen::Vector3d position = Eigen::Vector3d::Zero();  // m, the rock's centre
  std::string reason;                                  // the failure's own words
  // (source, run) order, that of a whole run's runs.
  bool operator<(const FailedTrajectory& other) const {
    return source != other.source ? source < other.source : run < other.run;
  }
};

// How far a run's envelope has converged (envelope_convergence.hpp). The whole run's change
// compares the union of every source's envelope before its last doubling of runs (n/2: the
// first half of a fixed run's runs) with the union after it (n).
struct ConvergenceReport {
  EnvelopeChange change;
  bool converged = false;               // change within the tolerance
  std::uint64_t sources = 0;            // sources simulated
  std::uint64_t sources_converged = 0;  // whose own envelope met the tolerance at its last doubling
  std::uint64_t sources_at_limit = 0;   // auto: stopped at run_limit without converging
  std::uint64_t run_limit = 0;          // auto: the most runs a source could get (auto_run_limit)
  // suggested_runs of the whole run's change: runs per source (fixed), or a run limit (auto).
  std::uint64_t runs_suggested = 0;
};

// The parts of a ConvergenceReport that add up over shares of the sources (SourceShare): the
// whole run's per-run maps before and after each source's last doubling, and source counts.
struct ConvergenceSums {
  explicit ConvergenceSums(std::size_t cells) : half(cells), all(cells) {}
  EnvelopeGrid half, all;
  std::uint64_t sources = 0, sources_converged = 0, sources_at_limit = 0;
};

// The report of the sums of a run with these settings.
ConvergenceReport convergence_report(const ConvergenceSums& sums, const RockfallSettings& settings);

// A rock that breaks (paper fig. 4, full mode) reports several fragments (trajectory_observer.hpp):
// its line and runout follow its first fragment only; stop_counts count every fragment's stop.
struct RockfallResult {
  RockfallStatistics statistics;
  std::vector<TrajectoryLine> lines;            // sorted by (source, run)
  std::vector<std::uint64_t> stop_counts;       // by StopReason, one per fragment (a rock that never broke is one)
  std::vector<double> runouts;                  // m, horizontal path length of every run simulated, in (source, run) order
  std::uint64_t trajectories = 0;
  int threads = 1;
  std::uint64_t fragments = 0;                  // extra rocks born from fractures, over all runs
  std::vector<std::uint64_t> runs_by_source;    // runs simulated per source (0: not selected)
  std::optional<ConvergenceReport> convergence; // none with only_run (one run per source)
  std::optional<ConvergenceSums> convergence_sums;  // what `convergence` is computed from
  // The recovery (docs/rockfall-full.md, section 5): runs whose first draw met a failed step (the
  // failures without recovery), runs drawn again from a fresh stream, and those that failed on
  // every draw, sorted by (source, run). `trajectories` counts the others.
  std::uint64_t troubled = 0;
  std::uint64_t redrawn = 0;
  std::vector<FailedTrajectory> failures;
};

// One release location: a cell centre (jittered inside its cell) or a point, with the
// conditions its release feature gives (empty: the run's rock, at rest, the run's
// release_height).
struct ReleaseSource {
  double x = 0, y = 0;           // m
  bool is_cell = true;
  ReleaseConditions conditions;
  std::int64_t feature_id = kNoReleaseFeature;  // FID of the release feature it comes from
};
std::vector<ReleaseSource> release_sources(const ReleaseSet& release);

// Every run of every source (or those only_source and only_run select, of settings.share): in batches per source,
// each batch's runs shared among the threads, the next batch of a source decided (auto_runs)
// from that source's envelope once its batch is done. A run that fails numerically
// (NumericalFailure) is drawn again from a fresh stream up to settings.redraws times, and then
// recorded in RockfallResult::failures; the others go on.
RockfallResult run_rockfall(const GroundModel& ground, const std::vector<ReleaseSource>& sources,
                            const TrajectoryModel& model, const RockfallSettings& settings, Progress* progress);

}  // namespace talus
