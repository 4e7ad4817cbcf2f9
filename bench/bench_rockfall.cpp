// Fast-mode trajectories per second on the sample scene, statistics included (issue 3,
// "Benchmark"). Arguments: threads. Reported counter: trajectories/s.
#include <benchmark/benchmark.h>

#include "sample_scene_inputs.hpp"
#include "talus/gis/scene.hpp"
#include "talus/rockfall/fast_bounce.hpp"
#include "talus/rockfall/monte_carlo.hpp"

namespace {

struct SampleScene {
  talus::gis::Scene scene;
  talus::GroundModel ground;
  std::vector<talus::ReleaseSource> sources;
};

const SampleScene& sample_scene() {
  static const SampleScene sample = [] {
    talus::gis::SceneInputs inputs = sample_scene_inputs();
    talus::gis::Scene scene = talus::gis::load_scene(inputs);
    talus::GroundModel ground = scene.ground_model();
    auto sources = talus::release_sources(*scene.release);
    return SampleScene{std::move(scene), std::move(ground), std::move(sources)};
  }();
  return sample;
}

void FastModeTrajectories(benchmark::State& state) {
  const SampleScene& sample = sample_scene();
  talus::RockfallSettings settings;
  settings.runs_per_source = 20;
  settings.threads = static_cast<int>(state.range(0));
  settings.saved_trajectories = 0;
  const talus::FastBounce model;
  std::uint64_t trajectories = 0;
  for (auto _ : state) {
    const talus::RockfallResult result = talus::run_rockfall(sample.ground, sample.sources, model, settings, nullptr);
    trajectories += result.trajectories;
    benchmark::DoNotOptimize(result.statistics.layers());
  }
  state.counters["trajectories/s"] = benchmark::Counter(static_cast<double>(trajectories), benchmark::Counter::kIsRate);
}

}  // namespace

BENCHMARK(FastModeTrajectories)->Arg(1)->Arg(2)->Unit(benchmark::kMillisecond)->UseRealTime()->MinTime(2.0);

BENCHMARK_MAIN();
