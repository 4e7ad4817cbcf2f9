// The stochastic simulation of paper 3.4 over all release sources x runs, in parallel with
// OpenMP, reproducible bit for bit whatever the thread count.
#include "talus/rockfall/monte_carlo.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <condition_variable>
#include <functional>
#include <limits>
#include <mutex>
#include <numbers>
#include <queue>
#include <string>
#include <utility>

#include "talus/core/counter_random.hpp"
#include "talus/ground/perlin_noise.hpp"
#include "talus/ground/perturbed_ground.hpp"
#include "talus/rockfall/release_rock.hpp"
#include "talus/rockfall/step_guard.hpp"

namespace talus {
namespace {

// Stochastic rock fall builds one Perlin table per trajectory: 2^8 entries keep that cheap
// while lattice points share a value only by a 1-in-256 chance.
constexpr int kTrajectoryNoiseTableBits = 8;

double vary(CounterRandom& random, double variation) { return random.uniform(1.0 - variation, 1.0 + variation); }

// Paper 3.4 gives the noise a frequency of the order of the rock's size; its slopes grow as the
// amplitude over that wavelength. The table's amplitudes are those a rock of noise_reference_size
// sees; a smaller rock sees them in proportion to its size, so that the noise's slopes do not
// steepen without bound as rocks get smaller (docs/ground-model.md, "Noise and rock size").
double noise_scale(const Rock& rock, const StochasticParameters& s) {
  return std::min(1.0, rock.axes.maxCoeff() / s.noise_reference_size);
}

// A uniformly random orientation (Shoemake 1992, from three uniform numbers).
Eigen::Quaterniond random_orientation(CounterRandom& random) {
  const double u1 = random.uniform(), u2 = random.uniform(), u3 = random.uniform();
  const double a = std::sqrt(1.0 - u1), b = std::sqrt(u1);
  const double two_pi = 2.0 * std::numbers::pi;
  return Eigen::Quaterniond(b * std::cos(two_pi * u3), a * std::sin(two_pi * u2), a * std::cos(two_pi * u2),
                            b * std::sin(two_pi * u3));
}

// Follows one run for its summary (path length, largest energy and stop reason of its first
// fragment, every fragment's stop) and, when the run is one of the saved sample, its first
// fragment's line; forwards everything to the statistics recorder.
// Thrown by a tile's RunObserver when a sample leaves the tile's halo (TileBounds).
struct ReachedTileEdge {};

class RunObserver final : public TrajectoryObserver {
 public:
  RunObserver(RockfallStatistics::Recorder& recorder, const std::optional<TileBounds>& tile)
      : recorder_(recorder), tile_(tile) {}
  // A new draw of a run: everything the last one reported is forgotten (its line's vertices too).
  void start(TrajectoryLine* line) {
    line_ = line;
    if (line_ != nullptr) line_->vertices.clear();
    restarted_ = false;
    path_length_ = 0;
    max_energy_ = 0;
    has_last_ = false;
    following_ = true;
    stops_.clear();
    fragments_ = 0;
  }
  void on_sample(const TrajectorySample& sample) override {
    if (tile_ && !tile_->contains(sample.position.x(), sample.position.y())) throw ReachedTileEdge{};
    last_sample_ = sample;
    recorder_.on_sample(sample);
    if (!following_) return;
    if (has_last_) path_length_ += (sample.position - last_).head<2>().norm();
    last_ = sample.position;
    has_last_ = true;
    max_energy_ = std::max(max_energy_, sample.kinetic_energy);
    if (line_ != nullptr) keep_vertex(sample);
  }
  void on_energy_loss(double x, double y, double friction, double deformation) override {
    recorder_.on_energy_loss(x, y, friction, deformation);
  }
  // The model has already reported `last` as the final sample (trajectory_observer.hpp). The first
  // stop ends the first fragment.
  void on_stop(const TrajectorySample& last, StopReason reason) override {
    if (following_ && line_ != nullptr) {
      line_->stop_reason = reason;
      line_->max_energy = max_energy_ / 1000.0;
      line_->runout_length = path_length_;
    }
    following_ = false;
    stops_.push_back(reason);
    recorder_.on_stop(last, reason);
  }
  void on_fragment(const TrajectorySample& start) override {
    ++fragments_;
    recorder_.on_fragment(start);
  }
  void on_restart(double) override { restarted_ = true; }
  bool restarted() const { return restarted_; }
  // The model was left by ReachedTileEdge: the trajectory stops at its last sample on the tile.
  void stop_at_tile_edge() { on_stop(last_sample_, StopReason::tile_edge); }
  double path_length() const { return path_length_; }
  // Appends the sample to the saved line unless it would end a zero-length segment.
  void keep_vertex(const TrajectorySample& sample) {
    auto& vertices = line_->vertices;
    if (!vertices.empty() && (sample.position - vertices.back().position).norm() < kShortestTrajectorySegment) return;
    vertices.push_back({sample.position, sample.time, sample.velocity.norm(), sample.kinetic_energy / 1000.0,
                        sample.jump_height});
  }
  const std::vector<StopReason>& stops() const { return stops_; }  // every fragment's, first fragment's first
  std::uint64_t fragments() const { return fragments_; }

 private:
  RockfallStatistics::Recorder& recorder_;
  const std::optional<TileBounds>& tile_;
  TrajectorySample last_sample_;
  TrajectoryLine* line_ = nullptr;
  double path_length_ = 0, max_energy_ = 0;
  Eigen::Vector3d last_ = Eigen::Vector3d::Zero();
  bool has_last_ = false;
  bool following_ = true;            // still on the first fragment
  bool restarted_ = false;           // the model restarted the rock after a failed step
  std::vector<StopReason> stops_;
  std::uint64_t fragments_ = 0;
};

// Everything one run draws from its own counter-based stream (seed, source, run).
struct RunDraws {
  Rock rock;
  RigidBodyState start;
  PerlinParameters noise;
  MaterialVariation variation;
};

// `draw` 0 is the run's own stream; a run drawn again after a numerical failure takes the next.
RunDraws draw_run(const GroundModel& ground, const ReleaseSource& source, const RockfallSettings& settings,
                  std::uint64_t source_index, std::uint64_t run, std::uint64_t draw) {
  const StochasticParameters& s = settings.stochastic;
  CounterRandom random(settings.seed, source_index, run, draw);
  RunDraws draws;
  draws.rock = release_rock(settings.rock, source.conditions);
  draws.rock.axes *= vary(random, s.size_variation);
  draws.rock.density *= vary(random, s.density_variation);
  draws.variation.restitution_normal = vary(random, s.restitution_variation);
  draws.variation.restitution_tangential = vary(random, s.restitution_variation);
  draws.variation.friction = vary(random, s.friction_variation);
  draws.noise.base_frequency = s.noise_frequency / draws.rock.axes.maxCoeff();
  draws.noise.amplitude = noise_scale(draws.rock, s);
  draws.noise.octaves = s.noise_octaves;
  draws.noise.seed = random.next_bits();
  draws.noise.table_bits = kTrajectoryNoiseTableBits;
  const GridSpec& spec = ground.spec();
  double x = source.x + s.release_jitter * (random.uniform() - 0.5) * spec.cell_width();
  double y = source.y + s.release_jitter * (random.uniform() - 0.5) * spec.cell_height();
  if (!ground.contains(x, y)) {
    x = source.x;
    y = source.y;
  }
  draws.start.orientation = random_orientation(random);
  draws.start.position = {x, y, 0.0};
  draws.start.velocity = release_velocity(source.conditions);
  return draws;
}

// The record of a run that failed on its last draw: the step's time, place and reason when the full
// model's guard gave up (StepFailure), otherwise the failure's message.
FailedTrajectory failed_trajectory(const NumericalFailure& failure, std::uint64_t source, std::uint64_t run) {
  FailedTrajectory failed{source, run, std::numeric_limits<double>::quiet_NaN(), Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN()), failure.what()};
  if (const auto* step = dynamic_cast<const StepFailure*>(&failure)) {
    failed.time = step->time;
    failed.position = step->position;
    failed.reason = step->reason;
  }
  return failed;
}

// Runs of one source that a thread takes at once.
constexpr std::uint64_t kChunkRuns = 8;

// (source, run), ordered as the runs of a whole run are.
using RunKey = std::pair<std::uint64_t, std::uint64_t>;

// The batches of a run_rockfall call (envelope_convergence.hpp): where each source's first batch
// ends and, once a batch is done, where the next one ends. A fixed run of N runs is two batches,
// [0, N/2) and [N/2, N), so that its envelope is tested at N/2 against N; auto starts likewise
// with [0, min_runs/2) and [min_runs/2, min_runs), then doubles a source's runs until its
// envelope has converged or the next doubling would pass the run limit; only_run is one batch.
class BatchRule {
 public:
  explicit BatchRule(const RockfallSettings& settings)
      : settings_(settings),
        limit_(settings.auto_runs ? auto_run_limit(settings.convergence) : settings.runs_per_source) {}

  bool tested() const { return !settings_.only_run; }  // the envelope is tested for convergence
  std::uint64_t limit() const { return limit_; }
  std::uint64_t first_run() const { return settings_.only_run.value_or(0); }
  std::uint64_t first_end() const {
    if (settings_.only_run) return *settings_.only_run + 1;
    const std::uint64_t full = settings_.auto_runs ? settings_.convergence.min_runs : settings_.runs_per_source;
    return full / 2 > 0 ? full / 2 : full;
  }
  // 0: the source is finished after `done` runs, whose last batch changed its envelope by `change`.
  std::uint64_t next_end(std::uint64_t done, const EnvelopeChange& change) const {
    if (settings_.only_run) return 0;
    if (!settings_.auto_runs) return done < settings_.runs_per_source ? settings_.runs_per_source : 0;
    if (done < settings_.convergence.min_runs) return settings_.convergence.min_runs;
    if (done >= limit_ || envelope_converged(change, settings_.convergence.tolerance)) return 0;
    return 2 * done;
  }
  // Runs a source is planned to take at most (progress), and those the saved lines sample from:
  // every run of a fixed run, the first min_runs of an auto run.
  std::uint64_t planned_runs() const { return settings_.only_run ? 1 : limit_; }
  std::uint64_t sampled_runs() const {
    if (settings_.only_run) return 1;
    return settings_.auto_runs ? settings_.convergence.min_runs : settings_.runs_per_source;
  }
  // Whether run `run` of the source at `position` among those simulated has its line saved.
  bool saved(std::uint64_t position, std::uint64_t run, std::uint64_t stride) const {
    if (settings_.only_run) return position % stride == 0;
    return run < sampled_runs() && (position * sampled_runs() + run) % stride == 0;
  }

 private:
  const RockfallSettings& settings_;
  std::uint64_t limit_;
};

// A share of the runs of one source's open batch, for one thread.
struct Chunk {
  std::size_t position = 0;  // the source's place among those simulated
  std::uint64_t begin = 0, end = 0;
  bool operator>(const Chunk& other) const {
    return position != other.position ? position > other.position : begin > other.begin;
  }
};

// The sources of a run_rockfall call, their batches and envelopes, shared by the threads: a
// queue of chunks, lowest source first (so that sources finish in order and few hold an
// envelope at a time). A source's batch is closed by the thread that finishes its last chunk:
// that source's envelope alone decides its next batch, so the decisions do not depend on the
// threads. Envelopes are integer sums compared in cell order, so they do not either.
class SourceBatches {
 public:
  SourceBatches(const RockfallSettings& settings, std::size_t source_count, std::size_t cells)
      : settings_(settings), rule_(settings), sums_(rule_.tested() ? cells : 0), runs_by_source_(source_count, 0) {
    for (std::uint64_t source = 0; source < source_count; ++source) {
      if (settings.only_source && *settings.only_source != source) continue;
      SourceState& state = states_.emplace_back();
      state.source = source;
      state.done = rule_.first_run();
    }
    for (std::size_t position = 0; position < states_.size(); ++position) {
      if (!settings.share.owns(position, states_[position].source)) continue;
      open_batch(position, rule_.first_end());
      ++owned_;
    }
  }

  const BatchRule& rule() const { return rule_; }
  std::size_t size() const { return states_.size(); }
  std::uint64_t source_at(std::size_t position) const { return states_[position].source; }

  // The next chunk to run; false once every batch is done or the run was cancelled.
  bool take(Chunk& chunk) {
    std::unique_lock<std::mutex> lock(mutex_);
    wake_.wait(lock, [&] { return cancelled_ || !queue_.empty() || in_flight_ == 0; });
    if (cancelled_ || queue_.empty()) return false;
    chunk = queue_.top();
    queue_.pop();
    ++in_flight_;
    return true;
  }

  // A chunk taken by take() is over: `completed` is false when it stopped early (the run is
  // cancelled); `crossed` is the cells its trajectories crossed (envelope_of merges them).
  void finish(const Chunk& chunk, bool completed, std::vector<EnvelopeCell>& crossed) {
    SourceState& state = states_[chunk.position];
    const Envelope envelope = completed && rule_.tested() ? envelope_of(std::move(crossed)) : Envelope{};
    crossed.clear();
    std::unique_lock<std::mutex> lock(mutex_);
    const bool closing = completed && !cancelled_ && merge_chunk(state, chunk, envelope);
    if (closing) {
      // This thread alone touches the source until its next batch is queued.
      lock.unlock();
      close_batch(state);
      lock.lock();
      const std::uint64_t next = rule_.next_end(state.done, state.change);
      if (next != 0) {
        open_batch(chunk.position, next);
      } else {
        finish_source(state);
      }
    }
    --in_flight_;
    wake_.notify_all();
  }

  void cancel() {
    const std::lock_guard<std::mutex> lock(mutex_);
    cancelled_ = true;
    wake_.notify_all();
  }

  // Sources finished plus, for each unfinished one, the share of its planned runs done: 0 .. 1.
  double fraction_done() {
    const std::lock_guard<std::mutex> lock(mutex_);
    return owned_ == 0 ? 1.0 : credit_ / static_cast<double>(owned_);
  }

  std::vector<std::uint64_t> runs_by_source() const { return runs_by_source_; }

  // The convergence sums of the sources this process simulated; none when untested.
  std::optional<ConvergenceSums> take_sums() {
    if (!rule_.tested()) return std::nullopt;
    sums_.sources = owned_;
    return std::move(sums_);
  }

 private:
  struct SourceState {
    std::uint64_t source = 0;
    std::uint64_t done = 0;       // runs of the closed batches (only_run: that run's index)
    std::uint64_t batch_end = 0;  // the open batch's runs end here
    std::uint64_t pending = 0;    // runs of the open batch not finished
    Envelope envelope;            // after the closed batches
    Envelope previous;            // before the last closed batch
    std::uint64_t previous_runs = 0;  // of `previous`
    Envelope batch;               // the open batch's finished chunks
    EnvelopeChange change;        // of the last closed batch
  };

  // Queues the chunks of a source's batch from its runs done to `end`. Under the lock.
  void open_batch(std::size_t position, std::uint64_t end) {
    SourceState& state = states_[position];
    state.batch_end = end;
    state.pending = end - state.done;
    for (std::uint64_t begin = state.done; begin < end; begin += kChunkRuns) {
      queue_.push({position, begin, std::min(end, begin + kChunkRuns)});
    }
  }

  // Adds a finished chunk to its batch; true when it was the batch's last. Under the lock.
  bool merge_chunk(SourceState& state, const Chunk& chunk, const Envelope& envelope) {
    if (!envelope.empty()) state.batch = envelope_sum(state.batch, envelope);
    state.pending -= chunk.end - chunk.begin;
    credit_ += static_cast<double>(chunk.end - chunk.begin) / static_cast<double>(rule_.planned_runs());
    return state.pending == 0;
  }

  // The batch joins the envelope; its change is measured. The source's own data only.
  static void close_batch(SourceState& state) {
    Envelope after = envelope_sum(state.envelope, state.batch);
    state.change = envelope_change(per_run(state.envelope, state.done), per_run(after, state.batch_end));
    state.previous_runs = state.done;
    state.previous = std::move(state.envelope);
    state.envelope = std::move(after);
    state.batch = Envelope{};
    state.done = state.batch_end;
  }

  // A source without further batches: its envelopes join the whole run's. Under the lock.
  void finish_source(SourceState& state) {
    if (rule_.tested()) {
      sums_.half.add(per_run(state.previous, state.previous_runs));
      sums_.all.add(per_run(state.envelope, state.done));
      const bool converged = envelope_converged(state.change, settings_.convergence.tolerance);
      sums_.sources_converged += converged ? 1 : 0;
      sums_.sources_at_limit += settings_.auto_runs && !converged ? 1 : 0;
    }
    runs_by_source_[state.source] = settings_.only_run ? 1 : state.done;
    credit_ += 1.0 - static_cast<double>(runs_by_source_[state.source]) / static_cast<double>(rule_.planned_runs());
    state.envelope = state.previous = Envelope{};
  }

  const RockfallSettings& settings_;
  BatchRule rule_;
  std::vector<SourceState> states_;
  std::size_t owned_ = 0;     // sources of settings.share
  ConvergenceSums sums_;
  std::vector<std::uint64_t> runs_by_source_;
  std::priority_queue<Chunk, std::vector<Chunk>, std::greater<>> queue_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::uint64_t in_flight_ = 0;  // chunks taken and not finished
  bool cancelled_ = false;
  double credit_ = 0;
};

}  // namespace

std::vector<ReleaseSource> release_sources(const ReleaseSet& release) {
  std::vector<ReleaseSource> sources;
  const GridSpec& spec = release.depth.spec();
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) {
      if (release.depth.at(col, row) > 0.0f) {
        sources.push_back({spec.node_x(col), spec.node_y(row), true, release.cell_conditions(col, row),
                           release.cell_feature(col, row)});
      }
    }
  }
  for (const auto& p : release.points) sources.push_back({p.x, p.y, false, p.conditions, p.feature_id});
  return sources;
}

ConvergenceReport convergence_report(const ConvergenceSums& sums, const RockfallSettings& settings) {
  const BatchRule rule(settings);
  ConvergenceReport report;
  report.change = envelope_change(sums.half.field(), sums.all.field());
  report.converged = envelope_converged(report.change, settings.convergence.tolerance);
  report.sources = sums.sources;
  report.sources_converged = sums.sources_converged;
  report.sources_at_limit = sums.sources_at_limit;
  report.run_limit = settings.auto_runs ? rule.limit() : 0;
  report.runs_suggested = suggested_runs(rule.limit(), report.change, settings.convergence.tolerance);
  return report;
}

RockfallResult run_rockfall(const GroundModel& ground, const std::vector<ReleaseSource>& sources,
                            const TrajectoryModel& model, const RockfallSettings& settings, Progress* progress) {
  SourceBatches batches(settings, sources.size(), ground.elevation_grid().size());
  const BatchRule& rule = batches.rule();
  const std::uint64_t sampled = batches.size() * rule.sampled_runs();
  const std::uint64_t save_stride =
      settings.saved_trajectories == 0 ? 0 : std::max<std::uint64_t>(1, (sampled + settings.saved_trajectories - 1) / settings.saved_trajectories);
  const int threads = settings.threads > 0 ? settings.threads : omp_get_max_threads();

  RockfallResult result{RockfallStatistics(ground.elevation_grid()), {}, std::vector<std::uint64_t>(kStopReasonCount, 0), {}, 0, threads, 0, {}, std::nullopt, std::nullopt, 0, 0, {}};
  std::vector<std::pair<RunKey, double>> runouts;
  std::atomic<bool> cancelled{false};

#pragma omp parallel num_threads(threads)
  {
    RockfallStatistics statistics(ground.elevation_grid());
    RockfallStatistics::Recorder recorder = statistics.recorder();
    RunObserver observer(recorder, settings.tile);
    std::vector<TrajectoryLine> lines;
    std::vector<std::uint64_t> stop_counts(kStopReasonCount, 0);
    std::vector<std::pair<RunKey, double>> thread_runouts;
    std::vector<EnvelopeCell> crossed;
    std::vector<FailedTrajectory> failures;
    std::uint64_t fragments = 0, troubled = 0, redrawn = 0;
    const bool reporter = omp_get_thread_num() == 0;

    Chunk chunk;
    while (batches.take(chunk)) {
      const std::uint64_t source_index = batches.source_at(chunk.position);
      const ReleaseSource& source = sources[source_index];
      std::uint64_t run = chunk.begin;
      for (; run < chunk.end && !cancelled.load(std::memory_order_relaxed); ++run) {
        TrajectoryLine* line = nullptr;
        if (save_stride != 0 && rule.saved(chunk.position, run, save_stride)) {
          lines.push_back({source_index, run, source.feature_id, StopReason::at_rest, 0, 0, {}});
          line = &lines.back();
        }
        // The recovery (docs/rockfall-full.md, section 5): a draw that fails numerically is
        // forgotten and the run drawn again from a fresh stream; the last draw's failure is kept.
        bool done = false;
        for (std::uint64_t draw = 0;; ++draw) {
          RunDraws draws = draw_run(ground, source, settings, source_index, run, draw);
          const PerlinNoise noise(draws.noise);
          const PerturbedGround perturbed(ground, &noise, draws.variation);
          draws.start.position.z() = perturbed.height(draws.start.position.x(), draws.start.position.y()) +
                                     draws.rock.half_height(draws.start.orientation) +
                                     source.conditions.release_height.value_or(settings.stochastic.release_height);
          observer.start(line);
          bool failed = false;
          try {
            model.run(perturbed, draws.rock, draws.start, observer);
          } catch (const NumericalFailure& e) {
            recorder.discard();
            failed = true;
            if (draw >= static_cast<std::uint64_t>(settings.redraws)) failures.push_back(failed_trajectory(e, source_index, run));
          } catch (const ReachedTileEdge&) {
            observer.stop_at_tile_edge();
          }
          if (draw == 0 && (failed || observer.restarted())) ++troubled;
          done = !failed;
          if (done || draw >= static_cast<std::uint64_t>(settings.redraws)) break;
          if (draw == 0) ++redrawn;
        }
        if (!done) {
          if (line != nullptr) lines.pop_back();
          continue;
        }
        if (rule.tested()) recorder.append_envelope(crossed);
        recorder.commit(source_index);
        thread_runouts.push_back({{source_index, run}, observer.path_length()});
        for (const StopReason reason : observer.stops()) ++stop_counts[static_cast<std::size_t>(reason)];
        fragments += observer.fragments();
      }
      batches.finish(chunk, run == chunk.end, crossed);
      if (reporter && progress != nullptr) {
        progress->report(batches.fraction_done(), "trajectories");
        if (progress->cancelled()) {
          cancelled.store(true);
          batches.cancel();
        }
      }
    }
#pragma omp critical(talus_rockfall_merge)
    {
      result.statistics.merge(statistics);
      for (std::size_t r = 0; r < stop_counts.size(); ++r) result.stop_counts[r] += stop_counts[r];
      result.fragments += fragments;
      result.troubled += troubled;
      result.redrawn += redrawn;
      for (auto& line : lines) result.lines.push_back(std::move(line));
      for (auto& failure : failures) result.failures.push_back(std::move(failure));
      runouts.insert(runouts.end(), thread_runouts.begin(), thread_runouts.end());
    }
  }
  if (cancelled.load()) throw Cancelled();
  std::sort(result.lines.begin(), result.lines.end(), [](const TrajectoryLine& a, const TrajectoryLine& b) {
    return a.source_id != b.source_id ? a.source_id < b.source_id : a.run_id < b.run_id;
  });
  std::sort(result.failures.begin(), result.failures.end());
  std::sort(runouts.begin(), runouts.end());
  result.runouts.reserve(runouts.size());
  for (const auto& [key, length] : runouts) result.runouts.push_back(length);
  result.trajectories = runouts.size();
  result.runs_by_source = batches.runs_by_source();
  result.convergence_sums = batches.take_sums();
  if (result.convergence_sums) result.convergence = convergence_report(*result.convergence_sums, settings);
  if (progress != nullptr) progress->report(1.0, "trajectories");
  return result;
}

}  // namespace talus
