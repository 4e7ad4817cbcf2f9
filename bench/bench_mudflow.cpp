// Mud-flow particle-steps per second on the sample scene (issue 5, "Benchmarks and chart"):
// the gully release of sample_dem/mudflow_release.gpkg (8056 m2, 1.8 m deep, about 14,500 m3)
// run for its first 40 simulated seconds with the default rheology (Voellmy), adaptive (released
// one particle per 5 m DEM cell, then fission, fusion and individual time steps) and uniform
// (one global step), with the finest particles 2.5 m (the default; 1284 particles when uniform)
// and 1.25 m (5136). Per-particle loops run on both threads while timed trials find that faster
// (MudflowSettings::parallel_check_period, docs/mudflow.md "Threads").
// Arguments: threads, adaptive (1) or uniform (0), finest particle size (mm).
// Counters: particle-steps/s (MudflowResult::particle_steps, one force evaluation of one
// particle, over the wall time of the run); particle-steps per CPU second (over the CPU time of
// the whole process, all threads: the figure that holds on a machine shared with other work,
// where a thread can wait for a core); per run, the particle-steps and the largest particle
// count. The CPU column is that of the whole process too.
#include <benchmark/benchmark.h>
#include <time.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <utility>

#include "sample_scene_inputs.hpp"
#include "talus/gis/scene.hpp"
#include "talus/mudflow/mudflow_simulation.hpp"

namespace {

// Simulated time (s) of one benchmark run: the release accelerates down the gully, so every
// part of the step loop (splits, merges, deep levels) is exercised, and a run takes seconds.
constexpr double kSimulatedSeconds = 40.0;

// CPU time of the whole process, all threads (s).
double process_cpu_seconds() {
  timespec now{};
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &now);
  return static_cast<double>(now.tv_sec) + 1e-9 * static_cast<double>(now.tv_nsec);
}

struct SampleFlowScene {
  talus::gis::Scene scene;
  talus::GroundModel ground;
};

// The sample scene with the mud-flow release, read through the gis layer as `talus mudflow`
// reads it (a `depth` attribute required).
const SampleFlowScene& sample_flow_scene() {
  static const SampleFlowScene sample = [] {
    talus::gis::SceneInputs inputs = sample_scene_inputs();
    inputs.release = std::filesystem::path(TALUS_SAMPLE_DIR) / "mudflow_release.gpkg";
    inputs.release_needs_depth = true;
    talus::gis::Scene scene = talus::gis::load_scene(inputs);
    talus::GroundModel ground = scene.ground_model();
    return SampleFlowScene{std::move(scene), std::move(ground)};
  }();
  return sample;
}

void MudflowParticleSteps(benchmark::State& state) {
  const SampleFlowScene& sample = sample_flow_scene();
  talus::MudflowSettings settings;
  settings.threads = static_cast<int>(state.range(0));
  settings.adaptive = state.range(1) != 0;
  settings.particle_size = 0.001 * static_cast<double>(state.range(2));
  settings.duration = kSimulatedSeconds;
  std::uint64_t particle_steps = 0;
  std::size_t peak_particles = 0;
  double cpu_seconds = 0;
  for (auto _ : state) {
    const double cpu_start = process_cpu_seconds();
    const talus::MudflowResult result = talus::run_mudflow(sample.ground, *sample.scene.release, nullptr, settings, nullptr);
    particle_steps += result.particle_steps;
    peak_particles = std::max(peak_particles, result.peak_particles);
    benchmark::DoNotOptimize(result.layers.deposit_depth);
    cpu_seconds += process_cpu_seconds() - cpu_start;
  }
  const auto iterations = static_cast<double>(state.iterations());
  state.counters["particle-steps/s"] =
      benchmark::Counter(static_cast<double>(particle_steps), benchmark::Counter::kIsRate);
  state.counters["particle-steps per CPU s"] = static_cast<double>(particle_steps) / cpu_seconds;
  state.counters["particle-steps"] = static_cast<double>(particle_steps) / iterations;
  state.counters["peak particles"] = static_cast<double>(peak_particles);
}

}  // namespace

BENCHMARK(MudflowParticleSteps)
    ->ArgNames({"threads", "adaptive", "size_mm"})
    ->ArgsProduct({{1, 2}, {1, 0}, {2500, 1250}})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->MeasureProcessCPUTime()
    ->Iterations(1);

BENCHMARK_MAIN();
