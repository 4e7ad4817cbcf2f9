// Full-model speed (issue 4, "Benchmarks and chart"; paper 2.2, 3.1-3.3): trajectories per
// second on the sample scene at 1 and 2 threads over a fixed subset of its release sources,
// and the cost of one 30 s fall of a 1 m sphere down a long rough slope on one core.
// Counters: trajectories/s (real time) and cpu_ms/trajectory (CPU time of all threads); for the
// fall, whose Time column is the time per fall: simulated_s (the simulated time it ran),
// travelled_m, max_time_reached (1 when it ran the whole 30 s). Figures:
// docs/rockfall-speed-accuracy.md and docs/performance.md.
#include <benchmark/benchmark.h>

#include <time.h>

#include <cmath>
#include <numbers>

#include "sample_scene_inputs.hpp"
#include "talus/gis/scene.hpp"
#include "talus/ground/perlin_noise.hpp"
#include "talus/ground/perturbed_ground.hpp"
#include "talus/rockfall/full_model.hpp"
#include "talus/rockfall/monte_carlo.hpp"

namespace {

// CPU time of the whole process, all threads (s): on a shared machine, the cost per trajectory
// that other work does not inflate.
double process_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

// Every kSourceStride-th release source of the sample scene (260 cliff points -> 26).
constexpr std::size_t kSourceStride = 10;

struct SampleScene {
  talus::gis::Scene scene;
  talus::GroundModel ground;
  std::vector<talus::ReleaseSource> sources;
};

// The sample scene with the built-in materials, read once (docs/architecture.md section 1: gis -> scene).
const SampleScene& sample_scene() {
  static const SampleScene sample = [] {
    talus::gis::SceneInputs inputs = sample_scene_inputs();
    talus::gis::Scene scene = talus::gis::load_scene(inputs);
    talus::GroundModel ground = scene.ground_model();
    const std::vector<talus::ReleaseSource> all = talus::release_sources(*scene.release);
    std::vector<talus::ReleaseSource> subset;
    for (std::size_t i = 0; i < all.size(); i += kSourceStride) subset.push_back(all[i]);
    return SampleScene{std::move(scene), std::move(ground), std::move(subset)};
  }();
  return sample;
}

// Paper 3.4 on the sample scene with the full model's default carpet and time steps: 4 runs
// per source (104 trajectories, enough chunks of the dynamic schedule for two threads to share
// evenly), statistics recorded and merged, layers computed.
void FullModeTrajectories(benchmark::State& state) {
  const SampleScene& sample = sample_scene();
  talus::RockfallSettings settings;
  settings.runs_per_source = 4;
  settings.threads = static_cast<int>(state.range(0));
  settings.saved_trajectories = 0;
  const talus::FullModel model;
  std::uint64_t trajectories = 0;
  const double cpu_start = process_cpu_seconds();
  for (auto _ : state) {
    const talus::RockfallResult result = talus::run_rockfall(sample.ground, sample.sources, model, settings, nullptr);
    trajectories += result.trajectories;
    benchmark::DoNotOptimize(result.statistics.layers());
  }
  const double cpu_seconds = process_cpu_seconds() - cpu_start;
  state.counters["trajectories/s"] = benchmark::Counter(static_cast<double>(trajectories), benchmark::Counter::kIsRate);
  state.counters["cpu_ms/trajectory"] = 1000.0 * cpu_seconds / static_cast<double>(trajectories);
}

// The long slope: a plane of the built-in "talus" class (code 4: k1 1e8 Pa/m, mu 0.4, Perlin
// roughness 0.3 m) falling towards +x at kSlopeAngle degrees, kSlopeLength m long and
// kSlopeWidth m wide in 5 m cells. Steep enough that a rolling and bouncing 1 m sphere never
// comes to rest, long enough that it is still on the slope after 30 s.
constexpr double kSlopeAngle = 30.0;    // deg
constexpr double kSlopeLength = 6000.0; // m, horizontal
constexpr double kSlopeWidth = 200.0;   // m
constexpr double kCellSize = 5.0;       // m

talus::GroundModel long_slope() {
  const talus::MaterialsTable table = talus::builtin_materials();
  const talus::GroundMaterial material = talus::GroundMaterial::from(*table.find_lithology(4), 0.0);
  talus::GridSpec spec;
  spec.width = static_cast<int>(kSlopeLength / kCellSize);
  spec.height = static_cast<int>(kSlopeWidth / kCellSize);
  spec.geotransform = {0.0, kCellSize, 0.0, kSlopeWidth, 0.0, -kCellSize};
  const double gradient = std::tan(kSlopeAngle * std::numbers::pi / 180.0);
  talus::Grid<double> elevation(spec);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) elevation.at(col, row) = gradient * (kSlopeLength - spec.node_x(col));
  }
  return talus::GroundModel(std::move(elevation), talus::Grid<talus::GroundMaterial>(spec, material));
}

// Keeps the last reported sample: how long the fall ran (s) and how far it went.
class LastSample final : public talus::TrajectoryObserver {
 public:
  void on_sample(const talus::TrajectorySample& sample) override { last_ = sample; }
  void on_energy_loss(double, double, double, double) override {}
  void on_stop(const talus::TrajectorySample& last, talus::StopReason reason) override {
    last_ = last;
    reason_ = reason;
  }
  const talus::TrajectorySample& last() const { return last_; }
  talus::StopReason reason() const { return reason_; }

 private:
  talus::TrajectorySample last_;
  talus::StopReason reason_ = talus::StopReason::at_rest;
};

// One 30 s fall (paper 3.3, full model, default carpet and steps) of a 1 m granite sphere
// (2700 kg/m3) released at rest 0.5 m above the rough slope, 50 m below its top, on one core.
void FullModeThirtySecondFall(benchmark::State& state) {
  const talus::GroundModel ground = long_slope();
  talus::PerlinParameters roughness;
  roughness.base_frequency = 1.0;   // 1/m: one wavelength per rock diameter, as the Monte Carlo runs
  roughness.amplitude = 1.0;        // scaled by the class's 0.3 m in PerturbedGround
  roughness.octaves = 3;
  roughness.seed = 7;
  const talus::PerlinNoise noise(roughness);
  const talus::PerturbedGround perturbed(ground, &noise);
  talus::FullModelParameters parameters;
  parameters.max_time = 30.0;
  const talus::FullModel model(parameters);
  const talus::Rock rock;
  talus::RigidBodyState start;
  start.position = {50.0, 0.5 * kSlopeWidth, 0.0};
  start.position.z() = perturbed.height(start.position.x(), start.position.y()) + 0.5 * rock.axes.x() + 0.5;
  LastSample observer;
  for (auto _ : state) {
    benchmark::DoNotOptimize(model.run(perturbed, rock, start, observer));
  }
  state.counters["simulated_s"] = observer.last().time;
  state.counters["travelled_m"] = observer.last().position.x() - start.position.x();
  state.counters["max_time_reached"] = observer.reason() == talus::StopReason::max_time ? 1.0 : 0.0;
}

}  // namespace

BENCHMARK(FullModeTrajectories)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);
BENCHMARK(FullModeThirtySecondFall)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

BENCHMARK_MAIN();
