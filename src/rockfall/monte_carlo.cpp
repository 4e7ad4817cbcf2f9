// The stochastic simulation of paper 3.4 over all release sources x runs, in parallel with
// OpenMP, reproducible bit for bit whatever the thread count.
#include "talus/rockfall/monte_carlo.hpp"

#include <omp.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <numbers>

#include "talus/core/counter_random.hpp"
#include "talus/ground/perlin_noise.hpp"
#include "talus/ground/perturbed_ground.hpp"
#include "talus/rockfall/release_rock.hpp"

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
class RunObserver final : public TrajectoryObserver {
 public:
  explicit RunObserver(RockfallStatistics::Recorder& recorder) : recorder_(recorder) {}
  void start(TrajectoryLine* line) {
    line_ = line;
    path_length_ = 0;
    max_energy_ = 0;
    has_last_ = false;
    following_ = true;
    stops_.clear();
    fragments_ = 0;
  }
  void on_sample(const TrajectorySample& sample) override {
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
  TrajectoryLine* line_ = nullptr;
  double path_length_ = 0, max_energy_ = 0;
  Eigen::Vector3d last_ = Eigen::Vector3d::Zero();
  bool has_last_ = false;
  bool following_ = true;            // still on the first fragment
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

RunDraws draw_run(const GroundModel& ground, const ReleaseSource& source, const RockfallSettings& settings,
                  std::uint64_t source_index, std::uint64_t run) {
  const StochasticParameters& s = settings.stochastic;
  CounterRandom random(settings.seed, source_index, run);
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

// The (source, run) pairs a run_rockfall call simulates, as flat indices source x runs + run, in
// order: all of them, or those RockfallSettings::only_source and only_run select.
std::vector<std::uint64_t> selected_runs(std::uint64_t sources, const RockfallSettings& settings) {
  const std::uint64_t runs = settings.runs_per_source;
  std::vector<std::uint64_t> selected;
  for (std::uint64_t source = 0; source < sources; ++source) {
    if (settings.only_source && *settings.only_source != source) continue;
    for (std::uint64_t run = 0; run < runs; ++run) {
      if (!settings.only_run || *settings.only_run == run) selected.push_back(source * runs + run);
    }
  }
  return selected;
}

RockfallResult run_rockfall(const GroundModel& ground, const std::vector<ReleaseSource>& sources,
                            const TrajectoryModel& model, const RockfallSettings& settings, Progress* progress) {
  const std::uint64_t runs = settings.runs_per_source;
  const std::vector<std::uint64_t> selected = selected_runs(sources.size(), settings);
  const std::uint64_t total = selected.size();
  const std::uint64_t save_stride =
      settings.saved_trajectories == 0 ? 0 : std::max<std::uint64_t>(1, (total + settings.saved_trajectories - 1) / settings.saved_trajectories);
  const int threads = settings.threads > 0 ? settings.threads : omp_get_max_threads();

  RockfallResult result{RockfallStatistics(ground.elevation_grid()), {}, std::vector<std::uint64_t>(4, 0),
                        std::vector<double>(total, 0.0), total, threads};
  std::atomic<std::uint64_t> done{0};
  std::atomic<bool> cancelled{false};
  // A run that throws (NumericalFailure: exit code 3) ends them all; the earliest such run's
  // failure is thrown, with its source and run, once every thread has left the loop.
  std::exception_ptr failure;
  std::uint64_t failed_run = 0;
  const auto keep_failure = [&](std::exception_ptr thrown, std::uint64_t k) {
#pragma omp critical(talus_rockfall_failure)
    if (failure == nullptr || k < failed_run) {
      failure = std::move(thrown);
      failed_run = k;
    }
    cancelled.store(true);
  };

#pragma omp parallel num_threads(threads)
  {
    RockfallStatistics statistics(ground.elevation_grid());
    RockfallStatistics::Recorder recorder = statistics.recorder();
    RunObserver observer(recorder);
    std::vector<TrajectoryLine> lines;
    std::vector<std::uint64_t> stop_counts(4, 0);
    std::uint64_t fragments = 0;
    const bool reporter = omp_get_thread_num() == 0;

#pragma omp for schedule(dynamic, 8)
    for (std::uint64_t n = 0; n < total; ++n) {
      if (cancelled.load(std::memory_order_relaxed)) continue;
      const std::uint64_t k = selected[n];
      const std::uint64_t source_index = k / runs, run = k % runs;
      RunDraws draws = draw_run(ground, sources[source_index], settings, source_index, run);
      const PerlinNoise noise(draws.noise);
      const PerturbedGround perturbed(ground, &noise, draws.variation);
      draws.start.position.z() = perturbed.height(draws.start.position.x(), draws.start.position.y()) +
                                 draws.rock.half_height(draws.start.orientation) +
                                 sources[source_index].conditions.release_height.value_or(settings.stochastic.release_height);
      TrajectoryLine* line = nullptr;
      if (save_stride != 0 && n % save_stride == 0) {
        lines.push_back({source_index, run, sources[source_index].feature_id, StopReason::at_rest, 0, 0, {}});
        line = &lines.back();
      }
      observer.start(line);
      try {
        model.run(perturbed, draws.rock, draws.start, observer);
      } catch (const NumericalFailure& e) {
        keep_failure(std::make_exception_ptr(TrajectoryFailure(e.what(), source_index, run)), k);
        continue;
      } catch (...) {
        keep_failure(std::current_exception(), k);
        continue;
      }
      recorder.commit(source_index);
      result.runouts[n] = observer.path_length();
      for (const StopReason reason : observer.stops()) ++stop_counts[static_cast<std::size_t>(reason)];
      fragments += observer.fragments();
      const std::uint64_t finished = done.fetch_add(1, std::memory_order_relaxed) + 1;
      if (reporter && progress != nullptr) {
        progress->report(static_cast<double>(finished) / static_cast<double>(total), "trajectories");
        if (progress->cancelled()) cancelled.store(true);
      }
    }
#pragma omp critical(talus_rockfall_merge)
    {
      result.statistics.merge(statistics);
      for (std::size_t r = 0; r < stop_counts.size(); ++r) result.stop_counts[r] += stop_counts[r];
      result.fragments += fragments;
      for (auto& line : lines) result.lines.push_back(std::move(line));
    }
  }
  if (failure != nullptr) std::rethrow_exception(failure);
  if (cancelled.load()) throw Cancelled();
  std::sort(result.lines.begin(), result.lines.end(), [](const TrajectoryLine& a, const TrajectoryLine& b) {
    return a.source_id != b.source_id ? a.source_id < b.source_id : a.run_id < b.run_id;
  });
  if (progress != nullptr) progress->report(1.0, "trajectories");
  return result;
}

}  // namespace talus
