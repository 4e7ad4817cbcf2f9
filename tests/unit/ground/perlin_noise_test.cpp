// Tests of the Perlin noise of paper 3.4 (hash table, bilinear Perlin0, octaves).
#include "talus/ground/perlin_noise.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <gtest/gtest.h>

#include "talus/core/counter_random.hpp"

namespace talus {
namespace {

// Tab[] has 4096 values uniform in [-1, 1]: standard deviation 1/sqrt(3).
constexpr double kTableSize = 4096.0;
const double kTableSd = 1.0 / std::sqrt(3.0);

PerlinNoise make_noise(double frequency, double amplitude, int octaves, std::uint64_t seed) {
  PerlinParameters parameters;
  parameters.base_frequency = frequency;
  parameters.amplitude = amplitude;
  parameters.octaves = octaves;
  parameters.seed = seed;
  return PerlinNoise(parameters);
}

double correlation(const std::vector<double>& a, const std::vector<double>& b) {
  const double n = static_cast<double>(a.size());
  double sa = 0, sb = 0, saa = 0, sbb = 0, sab = 0;
  for (std::size_t k = 0; k < a.size(); ++k) {
    sa += a[k];
    sb += b[k];
    saa += a[k] * a[k];
    sbb += b[k] * b[k];
    sab += a[k] * b[k];
  }
  const double cov = sab / n - sa / n * sb / n;
  return cov / std::sqrt((saa / n - sa / n * sa / n) * (sbb / n - sb / n * sb / n));
}

// Random points in [-half, half]^2 (negative lattice coordinates included).
std::vector<Eigen::Vector2d> random_points(int count, double half, std::uint64_t run) {
  CounterRandom random(77, 1, run);
  std::vector<Eigen::Vector2d> points;
  for (int k = 0; k < count; ++k) {
    const double x = random.uniform(-half, half);
    points.emplace_back(x, random.uniform(-half, half));
  }
  return points;
}

TEST(PerlinNoise, SameSeedGivesTheSameField) {
  const PerlinNoise first = make_noise(0.8, 0.2, 4, 31);
  const PerlinNoise second = make_noise(0.8, 0.2, 4, 31);
  for (const Eigen::Vector2d& p : random_points(2000, 100.0, 0)) {
    ASSERT_EQ(first(p.x(), p.y()), second(p.x(), p.y()));
    ASSERT_EQ(first.gradient(p.x(), p.y()), second.gradient(p.x(), p.y()));
  }
}

// Values and gradients of one field, recorded (as hexadecimal floats) from the implementation
// before the hash was shortened to the bits the table index reads: the same seed must keep
// giving the same field, and so the same layers, bit for bit (tolerance zero), at table sizes
// 2^8 (stochastic rock fall), 2^12 (the default) and 2^20, on both sides of the origin and at
// UTM-sized coordinates.
TEST(PerlinNoise, TheFieldOfASeedIsPinnedBitForBit) {
  struct Pinned {
    int table_bits;
    double x, y, value, dx, dy;
  };
  const Pinned pinned[] = {
      {8, 0.37, -1.62, 0x1.3e2458733c353p-5, -0x1.04427689fe1cap-4, 0x1.6f19eee2f27fep-8},
      {8, -12.71, 5.05, -0x1.5e82732bbc9bap-6, 0x1.99ba589fc217dp-5, 0x1.372e208e3390ep-2},
      {8, 612345.678, 5102345.125, 0x1.9702dfa09c79bp-10, -0x1.46033756d65e7p-3, 0x1.e37d759018b3dp-4},
      {8, -3000.25, -4000.75, -0x1.38ec0066d3391p-4, 0x1.1729feff065e7p-3, 0x1.54b04e622c1f2p-3},
      {12, 0.37, -1.62, -0x1.8772d2fdcbaf2p-4, 0x1.8e9e1ade75205p-3, 0x1.532f6ff52c886p-4},
      {12, -12.71, 5.05, -0x1.225c80bcba248p-4, 0x1.90016dab3da41p-3, 0x1.61b672294356bp-3},
      {12, 612345.678, 5102345.125, -0x1.08949873ef913p-4, 0x1.07d08f82dc2bap-3, -0x1.c515909b0da6bp-5},
      {12, -3000.25, -4000.75, -0x1.61483e4656f7p-7, 0x1.ad6540df4bbe8p-5, 0x1.f71c3170dae43p-3},
      {20, 0.37, -1.62, 0x1.0e758d3c95a62p-6, -0x1.b9dccfd8f4a5p-4, 0x1.38dba038af486p-5},
      {20, -12.71, 5.05, -0x1.62acdae50b9afp-4, 0x1.1ecbcd4bddecep-3, 0x1.649a97e953786p-4},
      {20, 612345.678, 5102345.125, -0x1.7ba5a37b167edp-13, 0x1.33bb8dfc7a32bp-3, -0x1.5faadafe87ap-4},
      {20, -3000.25, -4000.75, 0x1.539629517c6b8p-6, 0x1.0e6be89968154p-3, -0x1.9fac7245085b4p-8},
  };
  for (const Pinned& p : pinned) {
    PerlinParameters parameters;
    parameters.base_frequency = 0.9;
    parameters.amplitude = 0.25;
    parameters.octaves = 3;
    parameters.seed = 20261122;
    parameters.table_bits = p.table_bits;
    const PerlinNoise noise(parameters);
    const NoiseSample sample = noise.sample(p.x, p.y);
    EXPECT_EQ(noise(p.x, p.y), p.value) << p.table_bits << " " << p.x;
    EXPECT_EQ(sample.value, p.value) << p.table_bits << " " << p.x;
    EXPECT_EQ(sample.gradient.x(), p.dx) << p.table_bits << " " << p.x;
    EXPECT_EQ(sample.gradient.y(), p.dy) << p.table_bits << " " << p.x;
  }
}

TEST(PerlinNoise, DifferentSeedGivesAnotherField) {
  // At the lattice nodes of a one-octave field the noise is Tab[Hash(i, j)] itself, so two seeds
  // give two independent tables: the correlation is within 5 / sqrt(table size) of zero.
  const PerlinNoise first = make_noise(0.5, 1.0, 1, 1);
  const PerlinNoise second = make_noise(0.5, 1.0, 1, 2);
  std::vector<double> a, b;
  for (int i = -50; i < 50; ++i) {
    for (int j = -50; j < 50; ++j) {
      a.push_back(first(i / 0.5, j / 0.5));
      b.push_back(second(i / 0.5, j / 0.5));
    }
  }
  EXPECT_LT(std::abs(correlation(a, b)), 5.0 / std::sqrt(kTableSize));
  // With octaves, (almost) every point differs.
  const PerlinNoise third = make_noise(0.5, 1.0, 4, 1);
  const PerlinNoise fourth = make_noise(0.5, 1.0, 4, 2);
  int differ = 0;
  const auto points = random_points(1000, 100.0, 1);
  for (const Eigen::Vector2d& p : points) differ += third(p.x(), p.y()) != fourth(p.x(), p.y()) ? 1 : 0;
  EXPECT_GE(differ, 995);
}

TEST(PerlinNoise, TheHashRepeatsNeitherPeriodicallyNorSymmetrically) {
  // The hash is not the table index modulo its size: lattice nodes a table's length apart, or
  // mirrored, hold the same value only by a chance collision (1 in 4096).
  const PerlinNoise noise = make_noise(1.0, 1.0, 1, 5);
  int shifted = 0, swapped = 0, mirrored = 0;
  for (int i = 1; i <= 4096; ++i) {
    const double u = i, v = 3.0;
    shifted += noise(u, v) == noise(u + kTableSize, v) ? 1 : 0;
    swapped += noise(u, v) == noise(v, u) ? 1 : 0;
    mirrored += noise(u, v) == noise(-u, v) ? 1 : 0;
  }
  EXPECT_LT(shifted, 12);
  EXPECT_LT(swapped, 12);
  EXPECT_LT(mirrored, 12);
}

TEST(PerlinNoise, OneSampleEqualsValueAndGradient) {
  // sample() shares one pass over the octaves between the value and the gradient: the same bits.
  const PerlinNoise noise = make_noise(0.8, 0.3, 3, 17);
  for (const Eigen::Vector2d& p : random_points(500, 60.0, 4)) {
    const NoiseSample sample = noise.sample(p.x(), p.y());
    EXPECT_EQ(sample.value, noise(p.x(), p.y()));
    EXPECT_EQ(sample.gradient, noise.gradient(p.x(), p.y()));
  }
}

TEST(PerlinNoise, OctavesAreHalvedCopiesOfPerlin0AtDoubledFrequency) {
  // Perlin = (Perlin0(x) + 1/2 Perlin0(2x) + 1/4 Perlin0(4x) + ...) / (1 + 1/2 + 1/4 + ...).
  const PerlinNoise base = make_noise(0.3, 0.7, 1, 9);
  for (int octaves : {2, 3, 5}) {
    const PerlinNoise summed = make_noise(0.3, 0.7, octaves, 9);
    for (const Eigen::Vector2d& p : random_points(300, 80.0, 2)) {
      double expected = 0, weight_sum = 0;
      for (int k = 0; k < octaves; ++k) {
        const double scale = std::ldexp(1.0, k);
        expected += base(scale * p.x(), scale * p.y()) / scale;
        weight_sum += 1.0 / scale;
      }
      EXPECT_NEAR(summed(p.x(), p.y()), expected / weight_sum, 1e-12);
    }
  }
}

TEST(PerlinNoise, StaysWithinPlusMinusAmplitude) {
  // Every Perlin0 is a convex blend of table values in [-1, 1] and the octave weights are
  // normalised, so |Perlin| <= amplitude; it also comes close to it somewhere.
  for (int octaves : {1, 2, 4, 7}) {
    const double amplitude = 0.35;
    const PerlinNoise noise = make_noise(1.3, amplitude, octaves, 4);
    double largest = 0;
    for (const Eigen::Vector2d& p : random_points(40000, 60.0, 3)) {
      const double value = noise(p.x(), p.y());
      ASSERT_LE(std::abs(value), amplitude * (1.0 + 1e-12)) << "octaves " << octaves;
      largest = std::max(largest, std::abs(value));
    }
    EXPECT_GT(largest, 0.5 * amplitude) << "octaves " << octaves;
  }
}

TEST(PerlinNoise, MeanIsNearZeroOverALargeArea) {
  // The mean over M lattice cells is the mean of M table values: it departs from zero by the
  // table's own mean (sd kTableSd / sqrt(4096)) plus the sampling of the table (kTableSd /
  // sqrt(M)). Tolerance: four of these standard deviations.
  const double side = 400.0;  // m, with lambda = 1/m: M = 160000 lattice cells
  const double tolerance = 4.0 * kTableSd * std::sqrt(1.0 / kTableSize + 1.0 / (side * side));
  for (int octaves : {1, 4}) {
    for (std::uint64_t seed : {3u, 8u}) {
      const PerlinNoise noise = make_noise(1.0, 1.0, octaves, seed);
      double sum = 0;
      int count = 0;
      for (double y = -side / 2 + 0.13; y < side / 2; y += 0.71) {
        for (double x = -side / 2 + 0.29; x < side / 2; x += 0.53) {
          sum += noise(x, y);
          ++count;
        }
      }
      EXPECT_NEAR(sum / count, 0.0, tolerance) << "octaves " << octaves << " seed " << seed;
    }
  }
}

// Autocorrelation along x of a field sampled on rows far enough apart to be independent:
// result[m] for the lag m * step.
std::vector<double> autocorrelation_along_x(const PerlinNoise& noise, double step, int max_lag) {
  const int rows = 100, samples = 10000;
  const double row_spacing = 3.1;  // m, more than the support of the correlation
  std::vector<std::vector<double>> values(rows, std::vector<double>(samples));
  double sum = 0, sum_sq = 0;
  for (int r = 0; r < rows; ++r) {
    for (int n = 0; n < samples; ++n) {
      const double v = noise(0.123 + n * step, 0.377 + r * row_spacing);
      values[r][n] = v;
      sum += v;
      sum_sq += v * v;
    }
  }
  const double count = static_cast<double>(rows) * samples;
  const double mean = sum / count;
  const double variance = sum_sq / count - mean * mean;
  std::vector<double> rho(max_lag + 1);
  for (int m = 0; m <= max_lag; ++m) {
    double covariance = 0;
    for (const auto& row : values) {
      for (int n = 0; n + m < samples; ++n) covariance += (row[n] - mean) * (row[n + m] - mean);
    }
    rho[m] = covariance / (static_cast<double>(rows) * (samples - m)) / variance;
  }
  return rho;
}

// Lag where rho first falls to 1/2, linearly interpolated between samples.
double half_correlation_lag(const std::vector<double>& rho, double step) {
  for (std::size_t m = 1; m < rho.size(); ++m) {
    if (rho[m] <= 0.5) return step * (static_cast<double>(m) - 1.0 + (rho[m - 1] - 0.5) / (rho[m - 1] - rho[m]));
  }
  return -1.0;
}

// Correlation at lag s (in lattice cells) of bilinearly interpolated independent lattice values,
// averaged over positions: the tent's autocorrelation (a cubic B-spline) over its value at 0,
// 1 - 3/2 s^2 + 3/4 s^3 for s <= 1, (2 - s)^3 / 4 for 1 <= s <= 2, 0 beyond.
double value_noise_correlation(double s) {
  if (s <= 1.0) return 1.0 - 1.5 * s * s + 0.75 * s * s * s;
  if (s <= 2.0) return (2.0 - s) * (2.0 - s) * (2.0 - s) / 4.0;
  return 0.0;
}

TEST(PerlinNoise, CorrelationLengthFollowsTheBaseFrequency) {
  // Half-correlation lag in lattice cells, solved from value_noise_correlation (about 0.722).
  double low = 0.0, high = 1.0;
  for (int k = 0; k < 60; ++k) {
    const double middle = 0.5 * (low + high);
    if (value_noise_correlation(middle) > 0.5) {
      low = middle;
    } else {
      high = middle;
    }
  }
  const double half_lag_cells = 0.5 * (low + high);

  const double step = 0.0125;  // m, the same sampling for both frequencies
  const int max_lag = 200;     // 2.5 m
  const auto rho_1 = autocorrelation_along_x(make_noise(1.0, 1.0, 1, 12), step, max_lag);
  const auto rho_2 = autocorrelation_along_x(make_noise(2.0, 1.0, 1, 12), step, max_lag);
  const double half_1 = half_correlation_lag(rho_1, step);
  const double half_2 = half_correlation_lag(rho_2, step);
  EXPECT_NEAR(half_1 / half_2, 2.0, 0.15 * 2.0);
  EXPECT_NEAR(half_1, half_lag_cells / 1.0, 0.1 * half_lag_cells);
  EXPECT_NEAR(half_2, half_lag_cells / 2.0, 0.1 * half_lag_cells / 2.0);

  // At one lattice cell (lag 1/lambda) bilinear value noise still correlates by 1/4; from two
  // cells (lag 2/lambda) on, the four corners are independent and the correlation vanishes.
  EXPECT_NEAR(rho_1[80], value_noise_correlation(1.0), 0.04);  // lag 1 m = 1/lambda
  EXPECT_NEAR(rho_2[40], value_noise_correlation(1.0), 0.04);  // lag 0.5 m = 1/(2 lambda)
  for (int m = 160; m <= max_lag; m += 8) EXPECT_NEAR(rho_1[m], 0.0, 0.04) << "lag " << m * step << " m";
  for (int m = 80; m <= max_lag; m += 8) EXPECT_NEAR(rho_2[m], 0.0, 0.04) << "lag " << m * step << " m";
}

TEST(PerlinNoise, GradientMatchesFiniteDifferences) {
  const double frequency = 0.7;
  const int octaves = 4;
  const PerlinNoise noise = make_noise(frequency, 0.3, octaves, 21);
  const double h = 1e-6;  // m
  // A central difference straddling a lattice line of any octave would see the slope jump.
  const auto near_lattice_line = [&](double coordinate) {
    for (int k = 0; k < octaves; ++k) {
      const double u = frequency * std::ldexp(1.0, k) * coordinate;
      const double distance = std::abs(u - std::round(u));
      if (distance < 4.0 * h * frequency * std::ldexp(1.0, k)) return true;
    }
    return false;
  };
  int checked = 0;
  const auto points = random_points(2000, 50.0, 4);
  for (const Eigen::Vector2d& p : points) {
    if (near_lattice_line(p.x()) || near_lattice_line(p.y())) continue;
    const double x_plus = p.x() + h, x_minus = p.x() - h, y_plus = p.y() + h, y_minus = p.y() - h;
    const double d_dx = (noise(x_plus, p.y()) - noise(x_minus, p.y())) / (x_plus - x_minus);
    const double d_dy = (noise(p.x(), y_plus) - noise(p.x(), y_minus)) / (y_plus - y_minus);
    const Eigen::Vector2d gradient = noise.gradient(p.x(), p.y());
    EXPECT_NEAR(gradient.x(), d_dx, 1e-7) << p.transpose();
    EXPECT_NEAR(gradient.y(), d_dy, 1e-7) << p.transpose();
    ++checked;
  }
  EXPECT_GT(checked, 1900);
}

}  // namespace
}  // namespace talus
