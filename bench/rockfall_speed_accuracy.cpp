// Speed against accuracy of the rock-fall models on the sample scene (issue 4, "Benchmarks and
// chart"; docs/architecture.md section 4). The stochastic runs of paper 3.4 over a fixed subset of the
// release sources, with one seed for every configuration (the same release points, rocks and
// Perlin grounds), for: the full model of paper 2.2/3.3 at several piston-carpet spacings and
// time-step factors, and the fast bounce mode of paper 3.3 with the built-in materials table
// and, when given, a calibrated one (`talus calibrate`). Each is compared with the finest full
// model: median runout, two-sample Kolmogorov-Smirnov distance of the runouts, and the map of
// the reach probability per released block (passages / trajectories, docs/hazard-statistics.md).
// The reference run again with the next seed gives the Monte Carlo noise floor of each metric. Each configuration runs in a child process under a time limit,
// so that one that fails or never ends is reported and the sweep goes on. Writes one CSV row
// per configuration (columns and units: docs/rockfall-speed-accuracy.md);
// bench/plot_speed_accuracy.py draws the chart.
//
//   rockfall_speed_accuracy OUT.csv [--calibrated-materials F.toml] [--source-stride N]
//                           [--runs N] [--threads N] [--seed N] [--time-limit S]
// Defaults: every 5th source, 10 runs per source, 2 threads, seed 1, 240 s per configuration.
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "talus/core/errors.hpp"
#include "sample_scene_inputs.hpp"
#include "talus/gis/scene.hpp"
#include "talus/rockfall/fast_bounce.hpp"
#include "talus/rockfall/full_model.hpp"
#include "talus/rockfall/monte_carlo.hpp"

namespace {

struct Options {
  std::string csv_path;
  std::string calibrated_materials;   // empty: no "fast calibrated" row
  std::size_t source_stride = 5;      // every N-th release source of the scene
  std::uint64_t runs = 10;            // trajectories per source
  int threads = 2;
  std::uint64_t seed = 1;
  double time_limit = 240.0;          // s of wall time per configuration
};

// Bad usage: one line naming the problem, the usage, exit code 2 (docs/architecture.md section 3).
[[noreturn]] void usage_error(const std::string& message) {
  std::cerr << "rockfall_speed_accuracy: error: " << message << "\n"
            << "usage: rockfall_speed_accuracy OUT.csv [--calibrated-materials F.toml] [--source-stride N] [--runs N]"
               " [--threads N] [--seed N] [--time-limit S]\n";
  std::exit(2);
}

// The value of `flag` as an integer > 0, or a usage error.
std::uint64_t positive_integer(const std::string& flag, const std::string& text) {
  std::size_t used = 0;
  unsigned long long value = 0;
  try {
    value = std::stoull(text, &used);
  } catch (const std::exception&) {
    usage_error(flag + " needs a positive integer, got '" + text + "'");
  }
  if (used != text.size() || value == 0) usage_error(flag + " needs a positive integer, got '" + text + "'");
  return value;
}

// The command line (see the usage at the top of this file).
Options parse_options(int argc, char** argv) {
  Options options;
  for (int i = 1; i < argc; ++i) {
    const std::string argument = argv[i];
    if (argument.rfind("--", 0) != 0) {
      if (!options.csv_path.empty()) usage_error("more than one output path");
      options.csv_path = argument;
      continue;
    }
    if (i + 1 >= argc) usage_error(argument + " needs a value");
    const std::string value = argv[++i];
    if (argument == "--calibrated-materials") options.calibrated_materials = value;
    else if (argument == "--source-stride") options.source_stride = positive_integer(argument, value);
    else if (argument == "--runs") options.runs = positive_integer(argument, value);
    else if (argument == "--threads") options.threads = static_cast<int>(positive_integer(argument, value));
    else if (argument == "--seed") options.seed = positive_integer(argument, value);
    else if (argument == "--time-limit") options.time_limit = static_cast<double>(positive_integer(argument, value));
    else usage_error("unknown option " + argument);
  }
  if (options.csv_path.empty()) usage_error("no output path");
  return options;
}

// The sample scene's maps with the given materials table (empty: the built-in one) and every
// `stride`-th release source.
struct SampleScene {
  talus::GroundModel ground;
  std::vector<talus::ReleaseSource> sources;
};

// Reads the sample scene through the gis layer, as `talus rockfall` does (docs/architecture.md section 1).
SampleScene load_sample(const std::string& materials, std::size_t stride) {
  talus::gis::SceneInputs inputs = sample_scene_inputs();
  inputs.materials = materials;
  const talus::gis::Scene scene = talus::gis::load_scene(inputs);
  const std::vector<talus::ReleaseSource> all = talus::release_sources(*scene.release);
  std::vector<talus::ReleaseSource> subset;
  for (std::size_t i = 0; i < all.size(); i += stride) subset.push_back(all[i]);
  return SampleScene{scene.ground_model(), std::move(subset)};
}

// Forwards a run to its observer and keeps the last sample, so that a run cut short can be
// closed where it stood.
class LastSampleForwarder final : public talus::TrajectoryObserver {
 public:
  LastSampleForwarder(talus::TrajectoryObserver& target, const talus::RigidBodyState& start) : target_(target) {
    last_.position = start.position;
  }
  void on_sample(const talus::TrajectorySample& sample) override {
    last_ = sample;
    target_.on_sample(sample);
  }
  void on_energy_loss(double x, double y, double friction, double deformation) override {
    target_.on_energy_loss(x, y, friction, deformation);
  }
  void on_stop(const talus::TrajectorySample& last, talus::StopReason reason) override { target_.on_stop(last, reason); }
  const talus::TrajectorySample& last() const { return last_; }

 private:
  talus::TrajectoryObserver& target_;
  talus::TrajectorySample last_;
};

// A model whose runs that fail numerically (the full model's step guard gave up) are counted
// and end where they stood, instead of ending the whole configuration: a configuration with
// failed runs is reported as unstable.
class FailureCountingModel final : public talus::TrajectoryModel {
 public:
  explicit FailureCountingModel(const talus::TrajectoryModel& model) : model_(model) {}
  talus::StopReason run(const talus::PerturbedGround& ground, const talus::Rock& rock, talus::RigidBodyState start,
                        talus::TrajectoryObserver& observer) const override {
    LastSampleForwarder forwarder(observer, start);
    try {
      return model_.run(ground, rock, start, forwarder);
    } catch (const talus::NumericalFailure&) {
      failures_.fetch_add(1, std::memory_order_relaxed);
      observer.on_stop(forwarder.last(), talus::StopReason::at_rest);
      return talus::StopReason::at_rest;
    }
  }
  std::uint64_t failures() const { return failures_.load(); }

 private:
  const talus::TrajectoryModel& model_;
  mutable std::atomic<std::uint64_t> failures_{0};
};

// CPU time of the whole process, all threads (s).
double process_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

struct Configuration {
  std::string label;
  std::string mode;             // full | fast
  std::string materials;        // builtin | calibrated
  double carpet_spacing = 0;    // piston spacing / rock diameter (-), full mode only
  double time_step_factor = 0;  // (-), full mode only
  std::uint64_t seed = 0;
};

// What one configuration's runs give. Counts and times first: they travel from the child
// process as raw bytes, followed by the two arrays.
struct Outcome {
  struct Counts {
    double wall_seconds = 0;
    double cpu_seconds = 0;
    std::uint64_t trajectories = 0;
    std::uint64_t failures = 0;
    std::uint64_t max_time_stops = 0;
    std::uint64_t left_dem_stops = 0;
  } counts;
  std::vector<double> runouts;          // m, by (source, run)
  std::vector<float> reach_probability; // -, passages / trajectories per DEM cell, NaN outside the DEM's valid area
};

Outcome simulate(const SampleScene& sample, const talus::TrajectoryModel& model, const Options& options,
                 std::uint64_t seed) {
  talus::RockfallSettings settings;
  settings.runs_per_source = options.runs;
  settings.seed = seed;
  settings.threads = options.threads;
  settings.saved_trajectories = 0;
  const FailureCountingModel counted(model);
  const auto wall_start = std::chrono::steady_clock::now();
  const double cpu_start = process_cpu_seconds();
  talus::RockfallResult result = talus::run_rockfall(sample.ground, sample.sources, counted, settings, nullptr);
  const talus::RockfallLayers layers = result.statistics.layers();
  Outcome outcome;
  outcome.counts.cpu_seconds = process_cpu_seconds() - cpu_start;
  outcome.counts.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  outcome.counts.trajectories = result.trajectories;
  outcome.counts.failures = counted.failures();
  outcome.counts.max_time_stops = result.stop_counts[static_cast<std::size_t>(talus::StopReason::max_time)];
  outcome.counts.left_dem_stops = result.stop_counts[static_cast<std::size_t>(talus::StopReason::left_dem)];
  outcome.runouts = std::move(result.runouts);
  // Per released block, not the layer's per contributing source: one denominator for the
  // whole map, as this sweep has measured since issue 4.
  const talus::Grid<float>& passages = layers.passages;
  const double rocks = static_cast<double>(std::max<std::uint64_t>(result.trajectories, 1));
  outcome.reach_probability.resize(passages.size());
  for (std::size_t i = 0; i < passages.size(); ++i) {
    outcome.reach_probability[i] =
        passages.is_valid(i) ? static_cast<float>(passages[i] / rocks) : std::numeric_limits<float>::quiet_NaN();
  }
  return outcome;
}

// --- one configuration in a child process ---------------------------------------------------

// Raw bytes of `size` at `data`, appended (the child and the parent are the same program).
void append_bytes(std::string& bytes, const void* data, std::size_t size) {
  bytes.append(static_cast<const char*>(data), size);
}

// The outcome as bytes: counts, runout count and runouts, cell count and reach probabilities.
std::string serialise(const Outcome& outcome) {
  std::string bytes;
  append_bytes(bytes, &outcome.counts, sizeof outcome.counts);
  const std::uint64_t runouts = outcome.runouts.size(), cells = outcome.reach_probability.size();
  append_bytes(bytes, &runouts, sizeof runouts);
  append_bytes(bytes, outcome.runouts.data(), runouts * sizeof(double));
  append_bytes(bytes, &cells, sizeof cells);
  append_bytes(bytes, outcome.reach_probability.data(), cells * sizeof(float));
  return bytes;
}

// Reads what serialise() wrote; nullopt when the bytes are cut short.
std::optional<Outcome> deserialise(const std::string& bytes) {
  std::size_t at = 0;
  const auto take = [&](void* data, std::size_t size) {
    if (bytes.size() - at < size) return false;
    std::memcpy(data, bytes.data() + at, size);
    at += size;
    return true;
  };
  Outcome outcome;
  std::uint64_t count = 0;
  if (!take(&outcome.counts, sizeof outcome.counts) || !take(&count, sizeof count)) return std::nullopt;
  if (count > bytes.size() / sizeof(double)) return std::nullopt;
  outcome.runouts.resize(count);
  if (!take(outcome.runouts.data(), count * sizeof(double)) || !take(&count, sizeof count)) return std::nullopt;
  if (count > bytes.size() / sizeof(float)) return std::nullopt;
  outcome.reach_probability.resize(count);
  if (!take(outcome.reach_probability.data(), count * sizeof(float))) return std::nullopt;
  return outcome;
}

// Writes every byte to the pipe; a child that cannot exits with code 4.
void write_all(int fd, const std::string& bytes) {
  for (std::size_t at = 0; at < bytes.size();) {
    const ssize_t written = write(fd, bytes.data() + at, bytes.size() - at);
    if (written <= 0) _exit(4);
    at += static_cast<std::size_t>(written);
  }
}

// How a configuration ended (the CSV's `status` column).
enum class Status { ok, failed_runs, timed_out, crashed };
const char* to_string(Status status) {
  switch (status) {
    case Status::ok: return "ok";
    case Status::failed_runs: return "failed_runs";
    case Status::timed_out: return "timed_out";
    case Status::crashed: return "crashed";
  }
  return "crashed";
}

struct Attempt {
  Status status = Status::crashed;
  std::optional<Outcome> outcome;   // absent when timed out or crashed
};

// Runs simulate() in a child process (the parent itself never starts OpenMP threads, so the
// fork is safe) and reads its outcome through a pipe; a child still running after
// options.time_limit seconds is killed.
Attempt simulate_in_child(const SampleScene& sample, const talus::TrajectoryModel& model, const Options& options,
                          std::uint64_t seed) {
  int pipe_ends[2];
  if (pipe(pipe_ends) != 0) throw std::runtime_error("pipe failed");
  const pid_t child = fork();
  if (child < 0) throw std::runtime_error("fork failed");
  if (child == 0) {
    close(pipe_ends[0]);
    try {
      write_all(pipe_ends[1], serialise(simulate(sample, model, options, seed)));
    } catch (...) {
      _exit(3);
    }
    _exit(0);
  }
  close(pipe_ends[1]);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(options.time_limit);
  std::string bytes;
  bool timed_out = false;
  for (;;) {
    const double left = std::chrono::duration<double>(deadline - std::chrono::steady_clock::now()).count();
    if (left <= 0.0) {
      timed_out = true;
      break;
    }
    pollfd readable{pipe_ends[0], POLLIN, 0};
    if (poll(&readable, 1, static_cast<int>(std::ceil(left * 1000.0))) <= 0) continue;
    char buffer[65536];
    const ssize_t got = read(pipe_ends[0], buffer, sizeof buffer);
    if (got <= 0) break;
    bytes.append(buffer, static_cast<std::size_t>(got));
  }
  close(pipe_ends[0]);
  if (timed_out) kill(child, SIGKILL);
  int child_status = 0;
  waitpid(child, &child_status, 0);
  Attempt attempt;
  if (timed_out) {
    attempt.status = Status::timed_out;
    return attempt;
  }
  if (!WIFEXITED(child_status) || WEXITSTATUS(child_status) != 0) return attempt;
  attempt.outcome = deserialise(bytes);
  if (!attempt.outcome) return attempt;
  attempt.status = attempt.outcome->counts.failures > 0 ? Status::failed_runs : Status::ok;
  return attempt;
}

// --- comparison with the reference ----------------------------------------------------------

// Median of a sample (mean of the two middle values for an even count).
double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Two-sample Kolmogorov-Smirnov statistic: the largest difference between the two empirical
// distribution functions (-).
double kolmogorov_smirnov(std::vector<double> a, std::vector<double> b) {
  std::sort(a.begin(), a.end());
  std::sort(b.begin(), b.end());
  const double na = static_cast<double>(a.size()), nb = static_cast<double>(b.size());
  std::size_t i = 0, j = 0;
  double largest = 0.0;
  while (i < a.size() && j < b.size()) {
    const double x = std::min(a[i], b[j]);
    while (i < a.size() && a[i] == x) ++i;
    while (j < b.size() && b[j] == x) ++j;
    largest = std::max(largest, std::abs(static_cast<double>(i) / na - static_cast<double>(j) / nb));
  }
  return largest;
}

// Reach-probability maps compared over the valid cells that either reaches: the mean absolute
// difference (-) and the share of those cells reached by one and not the other (-).
struct ReachDifference {
  double mean_absolute = 0;
  double status_share = 0;
  std::size_t cells = 0;      // cells reached by either
};

ReachDifference reach_difference(const std::vector<float>& a, const std::vector<float>& reference) {
  ReachDifference difference;
  double sum = 0.0;
  std::size_t differing = 0;
  for (std::size_t i = 0; i < a.size() && i < reference.size(); ++i) {
    if (std::isnan(a[i]) || std::isnan(reference[i])) continue;
    const bool in_a = a[i] > 0.0f, in_reference = reference[i] > 0.0f;
    if (!in_a && !in_reference) continue;
    ++difference.cells;
    sum += std::abs(static_cast<double>(a[i]) - static_cast<double>(reference[i]));
    if (in_a != in_reference) ++differing;
  }
  if (difference.cells > 0) {
    difference.mean_absolute = sum / static_cast<double>(difference.cells);
    difference.status_share = static_cast<double>(differing) / static_cast<double>(difference.cells);
  }
  return difference;
}

// The CSV header, units in the names (docs/rockfall-speed-accuracy.md, "CSV columns").
void write_header(std::ofstream& csv) {
  csv << "configuration,mode,materials,carpet_spacing_diameters,time_step_factor,seed,status,trajectories,"
         "failed_trajectories,max_time_stops,left_dem_stops,wall_s,cpu_ms_per_trajectory,median_runout_m,"
         "median_runout_rel_error,ks_runout,reach_mean_abs_diff,reach_status_differs_share,cells_reached_either\n";
}

// One row; the measured columns stay empty for a configuration that timed out or crashed.
void write_row(std::ofstream& csv, const Configuration& configuration, const Attempt& attempt, const Outcome& reference) {
  char line[512];
  std::snprintf(line, sizeof line, "%s,%s,%s,%.6g,%.6g,%llu,%s", configuration.label.c_str(),
                configuration.mode.c_str(), configuration.materials.c_str(), configuration.carpet_spacing,
                configuration.time_step_factor, static_cast<unsigned long long>(configuration.seed),
                to_string(attempt.status));
  csv << line;
  if (!attempt.outcome) {
    csv << ",,,,,,,,,,,,\n";
    csv.flush();
    return;
  }
  const Outcome& outcome = *attempt.outcome;
  const Outcome::Counts& counts = outcome.counts;
  const double reference_median = median(reference.runouts);
  const double runout_median = median(outcome.runouts);
  const ReachDifference reach = reach_difference(outcome.reach_probability, reference.reach_probability);
  std::snprintf(line, sizeof line, ",%llu,%llu,%llu,%llu,%.3f,%.4g,%.2f,%.4f,%.4f,%.5f,%.4f,%zu\n",
                static_cast<unsigned long long>(counts.trajectories), static_cast<unsigned long long>(counts.failures),
                static_cast<unsigned long long>(counts.max_time_stops),
                static_cast<unsigned long long>(counts.left_dem_stops), counts.wall_seconds,
                1000.0 * counts.cpu_seconds / static_cast<double>(counts.trajectories), runout_median,
                (runout_median - reference_median) / reference_median, kolmogorov_smirnov(outcome.runouts, reference.runouts),
                reach.mean_absolute, reach.status_share, reach.cells);
  csv << line;
  csv.flush();
}

// "full 1/8 dt0.05": carpet spacing as a fraction of the diameter, then the time-step factor.
std::string full_label(double spacing, double factor) {
  char label[64];
  std::snprintf(label, sizeof label, "full 1/%ld dt%g", std::lround(1.0 / spacing), factor);
  return label;
}

// The full model (paper 2.2, 3.3) with its defaults but the carpet spacing (rock diameters) and
// the time-step factor (-).
talus::FullModel full_model(double spacing, double factor) {
  talus::FullModelParameters parameters;
  parameters.carpet_spacing = spacing;
  parameters.time_step_factor = factor;
  return talus::FullModel(parameters);
}

}  // namespace

int main(int argc, char** argv) {
  const Options options = parse_options(argc, argv);
  try {
    std::ofstream csv(options.csv_path);
    if (!csv) usage_error("cannot write " + options.csv_path);
    write_header(csv);
    const auto sweep_start = std::chrono::steady_clock::now();
    const SampleScene builtin = load_sample("", options.source_stride);
    std::cerr << builtin.sources.size() << " sources x " << options.runs << " runs, " << options.threads
              << " threads, seed " << options.seed << "\n";

    // The full model, finest first: the reference every row is compared with.
    const double spacings[] = {1.0 / 16.0, 1.0 / 8.0, 1.0 / 4.0};
    const double step_factors[] = {0.025, 0.05, 0.1};
    const Configuration reference_configuration{full_label(spacings[0], step_factors[0]), "full", "builtin",
                                                spacings[0], step_factors[0], options.seed};
    const Attempt reference = simulate_in_child(builtin, full_model(spacings[0], step_factors[0]), options, options.seed);
    if (reference.status != Status::ok) {
      std::cerr << "rockfall_speed_accuracy: error: the reference " << reference_configuration.label << " "
                << to_string(reference.status) << "\n";
      return 3;
    }
    const auto report = [&](const Configuration& configuration, const Attempt& attempt) {
      write_row(csv, configuration, attempt, *reference.outcome);
      std::cerr << configuration.label << ": " << to_string(attempt.status);
      if (attempt.outcome) {
        std::cerr << ", " << attempt.outcome->counts.wall_seconds << " s wall, " << attempt.outcome->counts.failures
                  << " failed runs";
      }
      std::cerr << "\n";
    };
    report(reference_configuration, reference);
    for (double spacing : spacings) {
      for (double factor : step_factors) {
        if (spacing == spacings[0] && factor == step_factors[0]) continue;
        report({full_label(spacing, factor), "full", "builtin", spacing, factor, options.seed},
               simulate_in_child(builtin, full_model(spacing, factor), options, options.seed));
      }
    }
    // The reference again with other draws: the Monte Carlo noise floor of every metric.
    report({reference_configuration.label + " other seed", "full", "builtin", spacings[0], step_factors[0],
            options.seed + 1},
           simulate_in_child(builtin, full_model(spacings[0], step_factors[0]), options, options.seed + 1));

    const talus::FastBounce fast;
    report({"fast builtin", "fast", "builtin", 0, 0, options.seed},
           simulate_in_child(builtin, fast, options, options.seed));
    if (!options.calibrated_materials.empty()) {
      const SampleScene calibrated = load_sample(options.calibrated_materials, options.source_stride);
      report({"fast calibrated", "fast", "calibrated", 0, 0, options.seed},
             simulate_in_child(calibrated, fast, options, options.seed));
    }
    std::cerr << "sweep: " << std::chrono::duration<double>(std::chrono::steady_clock::now() - sweep_start).count()
              << " s wall\n";
  } catch (const talus::InputError& error) {
    std::cerr << "rockfall_speed_accuracy: error: " << error.what() << "\n";
    return 2;
  }
  return 0;
}
