// Tests of the rock-fall statistical map (paper 3.4, "Gathering simulation data"; layers of
// docs/architecture.md section 3; docs/hazard-statistics.md): grid walk, per-passage statistics, sources
// per cell and the reach probability over their rocks, deposits, units, nodata, and merges that
// are bit-identical to a single accumulation whatever the split and the order.
#include "talus/rockfall/rockfall_statistics.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numeric>
#include <random>
#include <set>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "talus/core/grid.hpp"

namespace talus {
namespace {

constexpr int kWidth = 14;
constexpr int kHeight = 10;
constexpr double kX0 = 600000.0;
constexpr double kY0 = 5100000.0;
constexpr double kCell = 5.0;
constexpr float kNodata = -9999.0f;

// A DEM whose nodata value is 0 (layers must still use -9999), with a nodata cell and a NaN.
Grid<double> test_dem() {
  GridSpec spec;
  spec.width = kWidth;
  spec.height = kHeight;
  spec.geotransform = {kX0, kCell, 0.0, kY0, 0.0, -kCell};
  spec.crs_wkt = "EPSG:32632";
  spec.nodata = 0.0;
  Grid<double> dem(spec, 0.0);
  for (int row = 0; row < kHeight; ++row) {
    for (int col = 0; col < kWidth; ++col) dem.at(col, row) = 1500.0 - 10.0 * row + col;
  }
  dem.at(9, 6) = 0.0;
  dem.at(10, 6) = std::numeric_limits<double>::quiet_NaN();
  return dem;
}

// The x, y of a point given in cell coordinates (u along columns, v down the rows).
double x_at(double u) { return kX0 + u * kCell; }
double y_at(double v) { return kY0 - v * kCell; }

TrajectorySample sample_at(double u, double v, double energy, double jump_height, double speed) {
  TrajectorySample s;
  s.position = {x_at(u), y_at(v), 1400.0};
  s.velocity = {speed, 0.0, 0.0};
  s.kinetic_energy = energy;
  s.jump_height = jump_height;
  return s;
}

// One synthetic trajectory: a random walk of samples, with losses, then a stop.
struct Event {
  enum Kind { sample, loss } kind;
  TrajectorySample s;
  double friction = 0, deformation = 0;
};
struct Trajectory {
  std::vector<Event> events;
  TrajectorySample last;
  StopReason reason = StopReason::at_rest;
  std::uint64_t source = 0;
};

// Trajectories are released kRunsPerSource at a time from consecutive sources, as run_rockfall
// numbers them; 7 does not divide the chunks the merge tests split the runs into, so that the
// runs of some sources are recorded by two statistics.
constexpr std::size_t kRunsPerSource = 7;

std::vector<Trajectory> random_trajectories(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Trajectory> trajectories(count);
  for (std::size_t k = 0; k < count; ++k) {
    Trajectory& t = trajectories[k];
    t.source = k / kRunsPerSource;
    double u = 1.0 + unit(random) * (kWidth - 2);
    double v = 0.5 + unit(random) * 2.0;
    const int samples = 5 + static_cast<int>(unit(random) * 60);
    for (int i = 0; i < samples; ++i) {
      const double energy = unit(random) < 0.1 ? 0.0 : std::exp(2.0 + 12.0 * unit(random));
      const double jump = unit(random) < 0.3 ? 0.0 : 4.0 * unit(random) * unit(random);
      const TrajectorySample s = sample_at(u, v, energy, jump, 25.0 * unit(random));
      t.events.push_back({Event::sample, s});
      if (unit(random) < 0.4) {
        t.events.push_back({Event::loss, s, 1e4 * unit(random) * unit(random), unit(random) < 0.5 ? 0.0 : 3e4 * unit(random)});
      }
      t.last = s;
      // Mostly short steps downhill, sometimes a long one across several cells, sometimes
      // back uphill so that cells are revisited.
      const double length = unit(random) < 0.1 ? 1.5 + 3.0 * unit(random) : 0.4 * unit(random);
      const double angle = (unit(random) - 0.5) * 2.6 + (unit(random) < 0.1 ? 3.1 : 0.0);
      u += length * std::sin(angle);
      v += length * std::cos(angle);
    }
    t.reason = static_cast<StopReason>(static_cast<int>(unit(random) * 4) % 4);
  }
  return trajectories;
}

void record(RockfallStatistics::Recorder& recorder, const Trajectory& t) {
  for (const Event& e : t.events) {
    if (e.kind == Event::sample) {
      recorder.on_sample(e.s);
    } else {
      recorder.on_energy_loss(e.s.position.x(), e.s.position.y(), e.friction, e.deformation);
    }
  }
  recorder.on_stop(t.last, t.reason);
  recorder.commit(t.source);
}

RockfallStatistics record_all(const Grid<double>& dem, const std::vector<Trajectory>& trajectories,
                              std::size_t first = 0, std::size_t last = std::numeric_limits<std::size_t>::max()) {
  RockfallStatistics statistics(dem);
  RockfallStatistics::Recorder recorder = statistics.recorder();
  for (std::size_t i = first; i < std::min(last, trajectories.size()); ++i) record(recorder, trajectories[i]);
  return statistics;
}

std::vector<const Grid<float>*> all_layers(const RockfallLayers& l) {
  return {&l.reach_probability, &l.passages, &l.source_count, &l.deposits, &l.energy_max, &l.energy_p95,
          &l.jump_height_p95, &l.velocity_max, &l.energy_loss_friction, &l.energy_loss_deformation};
}

const char* const kLayerNames[] = {"reach_probability", "passages", "source_count", "deposits", "energy_max",
                                   "energy_p95", "jump_height_p95", "velocity_max", "energy_loss_friction",
                                   "energy_loss_deformation"};

void expect_same_bits(const RockfallLayers& a, const RockfallLayers& b, const std::string& what) {
  const auto la = all_layers(a);
  const auto lb = all_layers(b);
  for (std::size_t k = 0; k < la.size(); ++k) {
    ASSERT_EQ(la[k]->size(), lb[k]->size());
    std::size_t differing = 0;
    for (std::size_t i = 0; i < la[k]->size(); ++i) {
      differing += std::bit_cast<std::uint32_t>((*la[k])[i]) != std::bit_cast<std::uint32_t>((*lb[k])[i]);
    }
    EXPECT_EQ(differing, 0u) << what << ": layer " << kLayerNames[k];
  }
}

TEST(RockfallStatistics, MergedStatisticsEqualASingleComputation) {
  const Grid<double> dem = test_dem();
  const std::vector<Trajectory> trajectories = random_trajectories(300, 42);
  const RockfallStatistics single = record_all(dem, trajectories);
  ASSERT_EQ(single.rocks(), trajectories.size());
  const RockfallLayers expected = single.layers();
  // Every layer has values to compare: the comparison below is not vacuous.
  for (const Grid<float>* layer : all_layers(expected)) {
    EXPECT_GT(std::count_if(layer->values().begin(), layer->values().end(), [](float v) { return v > 0; }), 10);
  }
  std::mt19937_64 random(1);
  for (const std::size_t parts : {std::size_t{2}, std::size_t{3}, std::size_t{7}}) {
    // Contiguous chunks of uneven size, as threads with dynamic scheduling would take them.
    std::vector<RockfallStatistics> recorded;
    for (std::size_t p = 0; p < parts; ++p) {
      recorded.push_back(record_all(dem, trajectories, p * p * trajectories.size() / (parts * parts),
                                    (p + 1) * (p + 1) * trajectories.size() / (parts * parts)));
    }
    std::vector<std::size_t> order(parts);
    std::iota(order.begin(), order.end(), 0);
    for (int trial = 0; trial < 4; ++trial) {
      if (trial == 1) std::reverse(order.begin(), order.end());
      if (trial >= 2) std::shuffle(order.begin(), order.end(), random);
      RockfallStatistics merged(dem);
      for (const std::size_t p : order) merged.merge(recorded[p]);
      EXPECT_EQ(merged.rocks(), single.rocks());
      expect_same_bits(merged.layers(), expected, std::to_string(parts) + " parts, order " + std::to_string(trial));
    }
    // A tree of merges: the last part absorbs the others pairwise.
    RockfallStatistics left(dem);
    for (std::size_t p = 0; p < parts / 2; ++p) left.merge(recorded[p]);
    RockfallStatistics right(dem);
    for (std::size_t p = parts / 2; p < parts; ++p) right.merge(recorded[p]);
    right.merge(left);
    expect_same_bits(right.layers(), expected, std::to_string(parts) + " parts, tree");
  }
}

TEST(RockfallStatistics, ThreadsRecordingInParallelGiveTheSingleThreadLayers) {
  const Grid<double> dem = test_dem();
  const std::vector<Trajectory> trajectories = random_trajectories(400, 8);
  const RockfallLayers expected = record_all(dem, trajectories).layers();
  RockfallStatistics merged(dem);
  const auto count = static_cast<std::int64_t>(trajectories.size());
#pragma omp parallel num_threads(2)
  {
    RockfallStatistics local(dem);
    RockfallStatistics::Recorder recorder = local.recorder();
#pragma omp for schedule(dynamic, 3)
    for (std::int64_t i = 0; i < count; ++i) record(recorder, trajectories[static_cast<std::size_t>(i)]);
#pragma omp critical(rockfall_statistics_test_merge)
    merged.merge(local);
  }
  expect_same_bits(merged.layers(), expected, "2 threads");
}

TEST(RockfallStatistics, LayersAreDeterministic) {
  const Grid<double> dem = test_dem();
  const std::vector<Trajectory> trajectories = random_trajectories(100, 3);
  const RockfallStatistics a = record_all(dem, trajectories);
  expect_same_bits(a.layers(), a.layers(), "twice");
  expect_same_bits(a.layers(), record_all(dem, trajectories).layers(), "two runs");
}

// The oracle: each trajectory recorded alone tells the cells it crossed; a cell's sources are
// those of the trajectories that crossed it, and its reach probability is its passages over
// the rocks of those sources.
TEST(RockfallStatistics, SourceCountAndReachProbabilityFollowTheSourcesThatReachACell) {
  const Grid<double> dem = test_dem();
  const std::vector<Trajectory> trajectories = random_trajectories(250, 5);
  std::vector<std::set<std::uint64_t>> sources(dem.size());
  std::map<std::uint64_t, double> rocks_of;
  for (const Trajectory& t : trajectories) {
    const RockfallLayers alone = record_all(dem, {t}).layers();
    for (std::size_t i = 0; i < dem.size(); ++i) {
      if (alone.passages[i] > 0) sources[i].insert(t.source);
    }
    rocks_of[t.source] += 1;
  }
  const RockfallLayers layers = record_all(dem, trajectories).layers();
  std::size_t shared = 0;
  for (std::size_t i = 0; i < dem.size(); ++i) {
    if (!dem.is_valid(i)) continue;
    double rocks = 0;
    for (const std::uint64_t s : sources[i]) rocks += rocks_of[s];
    EXPECT_EQ(layers.source_count[i], static_cast<float>(sources[i].size())) << "cell " << i;
    const float expected = rocks > 0 ? static_cast<float>(layers.passages[i] / rocks) : 0.0f;
    EXPECT_EQ(layers.reach_probability[i], expected) << "cell " << i;
    EXPECT_LE(layers.reach_probability[i], 1.0f);
    shared += sources[i].size() > 1;
  }
  EXPECT_GT(shared, 20u);   // many cells are reached from several sources
}

// Unlike passages over every simulated rock, the reach probability does not fall when sources
// whose rocks never come near a cell are added, and it weighs each source by its own runs.
TEST(RockfallStatistics, ReachProbabilityCountsOnlyTheRocksOfTheSourcesThatReachTheCell) {
  const Grid<double> dem = test_dem();
  RockfallStatistics statistics(dem);
  RockfallStatistics::Recorder recorder = statistics.recorder();
  const auto roll = [&](double u0, double u1, double v, std::uint64_t source) {
    recorder.on_sample(sample_at(u0, v, 100.0, 0.1, 1.0));
    recorder.on_stop(sample_at(u1, v, 0.0, 0.0, 0.0), StopReason::at_rest);
    recorder.commit(source);
  };
  // Source 0: 2 rocks, both through cell (5, 2). Source 3: 6 rocks, 3 of them through (5, 2).
  roll(3.5, 5.5, 2.5, 0);
  roll(3.5, 6.5, 2.5, 0);
  for (int k = 0; k < 6; ++k) roll(k < 3 ? 7.5 : 8.5, k < 3 ? 5.5 : 9.5, 2.5, 3);
  // Source 1: 40 rocks far away, in row 8.
  for (int k = 0; k < 40; ++k) roll(1.5, 2.5, 8.5, 1);
  const RockfallLayers layers = statistics.layers();
  EXPECT_EQ(statistics.rocks(), 48u);
  EXPECT_EQ(layers.passages.at(5, 2), 5.0f);
  EXPECT_EQ(layers.source_count.at(5, 2), 2.0f);
  EXPECT_EQ(layers.reach_probability.at(5, 2), static_cast<float>(5.0 / 8.0));
  EXPECT_EQ(layers.reach_probability.at(3, 2), 1.0f);      // both rocks of source 0, none of source 3
  EXPECT_EQ(layers.source_count.at(3, 2), 1.0f);
  EXPECT_EQ(layers.reach_probability.at(9, 2), 0.5f);      // 3 of the 6 rocks of source 3
  EXPECT_EQ(layers.reach_probability.at(1, 8), 1.0f);
  EXPECT_EQ(layers.source_count.at(1, 8), 1.0f);
  EXPECT_EQ(layers.source_count.at(0, 0), 0.0f);
  EXPECT_EQ(layers.reach_probability.at(0, 0), 0.0f);
}

TEST(RockfallStatistics, DepositsOnlyForRocksAtRest) {
  const Grid<double> dem = test_dem();
  const std::vector<Trajectory> trajectories = random_trajectories(300, 6);
  std::vector<float> expected(dem.size(), 0.0f);
  for (const Trajectory& t : trajectories) {
    const double u = (t.last.position.x() - kX0) / kCell;
    const double v = (kY0 - t.last.position.y()) / kCell;
    if (t.reason != StopReason::at_rest || u < 0 || v < 0 || u >= kWidth || v >= kHeight) continue;
    expected[dem.index(static_cast<int>(u), static_cast<int>(v))] += 1.0f;
  }
  const RockfallLayers layers = record_all(dem, trajectories).layers();
  float total = 0;
  for (std::size_t i = 0; i < dem.size(); ++i) {
    if (!dem.is_valid(i)) continue;
    EXPECT_EQ(layers.deposits[i], expected[i]) << "cell " << i;
    total += layers.deposits[i];
  }
  EXPECT_GT(total, 20.0f);

  RockfallStatistics statistics(dem);
  RockfallStatistics::Recorder recorder = statistics.recorder();
  for (const StopReason reason : {StopReason::at_rest, StopReason::max_time, StopReason::left_dem, StopReason::nodata_area}) {
    recorder.on_sample(sample_at(2.5, 2.5, 100.0, 0.5, 1.0));
    recorder.on_stop(sample_at(3.5, 2.5, 0.0, 0.5, 0.0), reason);
    recorder.commit(0);
  }
  const RockfallLayers one = statistics.layers();
  EXPECT_EQ(one.deposits.at(3, 2), 1.0f);
  EXPECT_EQ(one.deposits.at(2, 2), 0.0f);
  EXPECT_EQ(one.passages.at(3, 2), 4.0f);
}

TEST(RockfallStatistics, NodataCellsAreNodataAndUnreachedCellsZero) {
  const Grid<double> dem = test_dem();
  RockfallStatistics statistics(dem);
  RockfallStatistics::Recorder recorder = statistics.recorder();
  // Across the nodata (9, 6) and NaN (10, 6) cells, with losses there.
  recorder.on_sample(sample_at(8.5, 6.5, 1e5, 1.0, 10.0));
  recorder.on_energy_loss(x_at(9.5), y_at(6.5), 500.0, 800.0);
  recorder.on_sample(sample_at(11.5, 6.5, 1e5, 1.0, 10.0));
  recorder.on_stop(sample_at(11.5, 6.5, 0.0, 0.5, 0.0), StopReason::at_rest);
  recorder.commit(0);
  const RockfallLayers layers = statistics.layers();
  for (const Grid<float>* layer : all_layers(layers)) {
    EXPECT_EQ(layer->spec().nodata, -9999.0);
    EXPECT_TRUE(layer->spec().same_grid(dem.spec()));
    EXPECT_EQ(layer->at(9, 6), kNodata);
    EXPECT_EQ(layer->at(10, 6), kNodata);
    EXPECT_EQ(layer->at(0, 0), 0.0f);      // valid, never reached
    EXPECT_EQ(layer->at(13, 9), 0.0f);
  }
  EXPECT_EQ(layers.passages.at(8, 6), 1.0f);
  EXPECT_EQ(layers.passages.at(11, 6), 1.0f);
  EXPECT_EQ(layers.deposits.at(11, 6), 1.0f);
}

TEST(RockfallStatistics, EnergiesInKilojoulesAndLossesMeanPerSimulatedRock) {
  const Grid<double> dem = test_dem();
  RockfallStatistics statistics(dem);
  RockfallStatistics::Recorder recorder = statistics.recorder();
  // Rock 1 stays in cell (2, 1) with 250 kJ, 1.5 m jumps, 12 m/s, and loses energy there.
  recorder.on_sample(sample_at(2.2, 1.5, 2.5e5, 1.5, 12.0));
  recorder.on_energy_loss(x_at(2.3), y_at(1.5), 3000.0, 1000.0);
  recorder.on_sample(sample_at(2.6, 1.5, 2.5e5, 1.5, 12.0));
  recorder.on_energy_loss(x_at(2.6), y_at(1.5), 1000.0, 0.0);
  recorder.on_stop(sample_at(2.6, 1.5, 2.5e5, 1.5, 12.0), StopReason::max_time);
  recorder.commit(0);
  // Rock 2 elsewhere.
  recorder.on_sample(sample_at(6.5, 7.5, 10.0, 0.0, 1.0));
  recorder.on_stop(sample_at(6.5, 7.5, 0.0, 0.0, 0.0), StopReason::at_rest);
  recorder.commit(0);
  EXPECT_EQ(statistics.rocks(), 2u);
  const RockfallLayers layers = statistics.layers();
  EXPECT_EQ(layers.energy_max.at(2, 1), 250.0f);
  const double ratio = std::pow(10.0, 0.05);   // one bin of the quantile estimator
  EXPECT_GT(layers.energy_p95.at(2, 1), 250.0 / ratio);
  EXPECT_LE(layers.energy_p95.at(2, 1), 250.0 * ratio);
  EXPECT_GT(layers.jump_height_p95.at(2, 1), 1.5 / ratio);
  EXPECT_LE(layers.jump_height_p95.at(2, 1), 1.5 * ratio);
  EXPECT_EQ(layers.velocity_max.at(2, 1), 12.0f);
  EXPECT_EQ(layers.energy_loss_friction.at(2, 1), 2.0f);        // 4 kJ over 2 rocks
  EXPECT_EQ(layers.energy_loss_deformation.at(2, 1), 0.5f);     // 1 kJ over 2 rocks
  EXPECT_EQ(layers.reach_probability.at(2, 1), 0.5f);
  EXPECT_EQ(layers.energy_max.at(6, 7), 0.01f);                 // 10 J
  EXPECT_GT(layers.energy_p95.at(6, 7), 0.01 / ratio);
  EXPECT_LE(layers.energy_p95.at(6, 7), 0.01 * ratio);
  EXPECT_EQ(layers.jump_height_p95.at(6, 7), 0.0f);             // rolling: 0 m counts as 0
  EXPECT_EQ(layers.energy_loss_friction.at(6, 7), 0.0f);
}

TEST(RockfallStatistics, LongSegmentsReachEveryCellTheyCross) {
  const Grid<double> dem = test_dem();
  RockfallStatistics statistics(dem);
  RockfallStatistics::Recorder recorder = statistics.recorder();
  // One 40 m segment from the middle of cell (0, 3) to the middle of cell (8, 3), the energy
  // rising linearly from 0 to 8 kJ: a cell's largest energy is the one where the path leaves it.
  recorder.on_sample(sample_at(0.5, 3.5, 0.0, 0.0, 0.0));
  recorder.on_sample(sample_at(8.5, 3.5, 8000.0, 2.0, 16.0));
  recorder.on_stop(sample_at(8.5, 3.5, 8000.0, 2.0, 16.0), StopReason::max_time);
  recorder.commit(0);
  // And a diagonal one through lattice corners, (0.5, 4.5) -> (5.5, 9.5): only the diagonal cells.
  recorder.on_sample(sample_at(0.5, 4.5, 1.0, 0.0, 1.0));
  recorder.on_stop(sample_at(5.5, 9.5, 1.0, 0.0, 1.0), StopReason::max_time);
  recorder.commit(0);
  const RockfallLayers layers = statistics.layers();
  for (int col = 0; col < kWidth; ++col) {
    const bool crossed = col <= 8;
    EXPECT_EQ(layers.passages.at(col, 3), crossed ? 1.0f : 0.0f) << col;
    if (!crossed) continue;
    const double exit_u = std::min(col + 1.0, 8.5);
    EXPECT_FLOAT_EQ(layers.energy_max.at(col, 3), static_cast<float>(8.0 * (exit_u - 0.5) / 8.0));
    EXPECT_FLOAT_EQ(layers.velocity_max.at(col, 3), static_cast<float>(16.0 * (exit_u - 0.5) / 8.0));
  }
  for (int row = 4; row < kHeight; ++row) {
    for (int col = 0; col < 6; ++col) {
      EXPECT_EQ(layers.passages.at(col, row), row - col == 4 ? 1.0f : 0.0f) << col << "," << row;
    }
  }
}

TEST(RockfallStatistics, APassageCountsOncePerTrajectory) {
  const Grid<double> dem = test_dem();
  RockfallStatistics statistics(dem);
  RockfallStatistics::Recorder recorder = statistics.recorder();
  // Back and forth between cells (4, 4) and (5, 4) five times.
  for (int k = 0; k < 10; ++k) recorder.on_sample(sample_at(k % 2 ? 5.5 : 4.5, 4.5, 100.0 * (k + 1), 0.1, 1.0));
  recorder.on_stop(sample_at(5.5, 4.5, 0.0, 0.0, 0.0), StopReason::at_rest);
  recorder.commit(0);
  const RockfallLayers layers = statistics.layers();
  EXPECT_EQ(layers.passages.at(4, 4), 1.0f);
  EXPECT_EQ(layers.passages.at(5, 4), 1.0f);
  EXPECT_EQ(layers.deposits.at(5, 4), 1.0f);
  EXPECT_FLOAT_EQ(layers.energy_max.at(5, 4), 1.0f);      // the largest of the ten samples, 1 kJ
  EXPECT_FLOAT_EQ(layers.energy_max.at(4, 4), 0.95f);     // 0.9 -> 1 kJ, at the shared edge
  EXPECT_EQ(layers.reach_probability.at(4, 4), 1.0f);
}

TEST(RockfallStatistics, RefusesToMergeStatisticsOfAnotherGrid) {
  const Grid<double> dem = test_dem();
  GridSpec other_spec = dem.spec();
  other_spec.geotransform[0] += 100.0;
  RockfallStatistics a(dem);
  EXPECT_THROW(a.merge(RockfallStatistics(Grid<double>(other_spec, 1.0))), GridMismatch);
}

// Paper fig. 4: a rock that broke reports its fragments one after the other. Each fragment's
// path starts anew (not joined to the last sample), a cell crossed by both counts one passage,
// and every fragment at rest is a deposit of the same simulated rock.
TEST(RockfallStatistics, FragmentsShareOnePassagePerCellAndDepositEach) {
  RockfallStatistics statistics(test_dem());
  RockfallStatistics::Recorder recorder = statistics.recorder();
  recorder.on_sample(sample_at(1.5, 1.5, 2000.0, 1.0, 5.0));
  recorder.on_sample(sample_at(3.5, 1.5, 1000.0, 1.0, 4.0));
  recorder.on_stop(sample_at(3.5, 1.5, 0.0, 0.0, 0.0), StopReason::at_rest);
  recorder.on_fragment(sample_at(2.5, 4.5, 5000.0, 2.0, 6.0));
  recorder.on_sample(sample_at(3.5, 4.5, 100.0, 1.0, 3.0));
  recorder.on_sample(sample_at(3.5, 1.5, 50.0, 1.0, 1.0));
  recorder.on_stop(sample_at(3.5, 1.5, 0.0, 0.0, 0.0), StopReason::at_rest);
  recorder.commit(0);
  const RockfallLayers layers = statistics.layers();
  const auto at = [](const Grid<float>& layer, int col, int row) { return layer.at(col, row); };
  EXPECT_EQ(statistics.rocks(), 1u);
  EXPECT_EQ(at(layers.deposits, 3, 1), 2.0f);           // both fragments rest in cell (3, 1)
  EXPECT_EQ(at(layers.passages, 3, 1), 1.0f);           // ...which counts one passage
  EXPECT_EQ(at(layers.reach_probability, 3, 1), 1.0f);
  EXPECT_EQ(at(layers.passages, 2, 1), 1.0f);           // first fragment's path
  EXPECT_EQ(at(layers.passages, 2, 4), 1.0f);           // second fragment's start
  EXPECT_EQ(at(layers.passages, 3, 3), 1.0f);           // its path back up to row 1
  EXPECT_EQ(at(layers.passages, 2, 3), 0.0f);           // not joined from (3.5, 1.5) to (2.5, 4.5)
  EXPECT_EQ(at(layers.energy_max, 2, 4), 5.0f);         // kJ: the fragment's own energy
  // kJ: the largest of both fragments' energies in the shared cell: 1250 J where the first enters it
  EXPECT_EQ(at(layers.energy_max, 3, 1), 1.25f);
}

}  // namespace
}  // namespace talus
