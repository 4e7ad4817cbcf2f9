// Rock-fall sources from the slope angle distribution (rockfall_source_detection.hpp; Loye et
// al. 2009).
#include "talus/hazard/rockfall_source_detection.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

namespace talus {
namespace {

constexpr double kBinWidth = 0.5;          // degrees
constexpr int kBins = 180;                 // 0 to 90 degrees
constexpr int kIterations = 2000;          // EM iterations at most
constexpr double kConvergence = 1e-10;     // relative change of the log-likelihood
constexpr double kSmallestSd = 1.0;        // degrees: keeps a unit from collapsing onto one bin

double density(const SlopeUnit& u, double x) {
  const double z = (x - u.mean) / u.sd;
  return u.weight * std::exp(-0.5 * z * z) / (u.sd * std::sqrt(2.0 * std::numbers::pi));
}

}  // namespace

// Horn (1981): dz/dx and dz/dy from the eight neighbours, weights 1-2-1.
Grid<float> slope_angles(const Grid<double>& elevation) {
  const GridSpec& spec = elevation.spec();
  Grid<float> slopes(spec, static_cast<float>(spec.nodata));
  const double dx = spec.cell_width(), dy = spec.cell_height();
  for (int row = 1; row + 1 < spec.height; ++row) {
    for (int col = 1; col + 1 < spec.width; ++col) {
      double z[3][3];
      bool valid = true;
      for (int r = -1; r <= 1 && valid; ++r) {
        for (int c = -1; c <= 1 && valid; ++c) {
          valid = elevation.is_valid(col + c, row + r);
          if (valid) z[r + 1][c + 1] = elevation[elevation.index(col + c, row + r)];
        }
      }
      if (!valid) continue;
      const double gx = ((z[0][2] + 2 * z[1][2] + z[2][2]) - (z[0][0] + 2 * z[1][0] + z[2][0])) / (8 * dx);
      const double gy = ((z[2][0] + 2 * z[2][1] + z[2][2]) - (z[0][0] + 2 * z[0][1] + z[0][2])) / (8 * dy);
      slopes[slopes.index(col, row)] = static_cast<float>(std::atan(std::hypot(gx, gy)) * 180.0 / std::numbers::pi);
    }
  }
  return slopes;
}

std::array<SlopeUnit, 4> slope_units(const Grid<float>& slopes) {
  std::vector<double> counts(kBins, 0.0);
  double total = 0;
  for (std::size_t cell = 0; cell < slopes.size(); ++cell) {
    if (!slopes.is_valid(cell)) continue;
    counts[std::clamp(static_cast<int>(slopes[cell] / kBinWidth), 0, kBins - 1)] += 1.0;
    total += 1.0;
  }
  std::array<SlopeUnit, 4> units = {{{0.25, 5, 5}, {0.25, 20, 5}, {0.25, 35, 5}, {0.25, 55, 8}}};
  if (total == 0) return units;
  double previous = -1e300;
  std::vector<std::array<double, 4>> share(kBins);
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    // E step: each bin's share in each unit, and the log-likelihood.
    double log_likelihood = 0;
    for (int b = 0; b < kBins; ++b) {
      if (counts[b] == 0) continue;
      const double x = (b + 0.5) * kBinWidth;
      double sum = 0;
      for (int k = 0; k < 4; ++k) sum += share[b][k] = density(units[k], x);
      if (!(sum > 0)) {
        share[b] = {0.25, 0.25, 0.25, 0.25};
        continue;
      }
      for (double& s : share[b]) s /= sum;
      log_likelihood += counts[b] * std::log(sum);
    }
    // M step: each unit's weight, mean and standard deviation from its shares.
    for (int k = 0; k < 4; ++k) {
      double n = 0, m = 0;
      for (int b = 0; b < kBins; ++b) {
        n += counts[b] * share[b][k];
        m += counts[b] * share[b][k] * (b + 0.5) * kBinWidth;
      }
      if (!(n > 0)) continue;
      m /= n;
      double v = 0;
      for (int b = 0; b < kBins; ++b) {
        const double d = (b + 0.5) * kBinWidth - m;
        v += counts[b] * share[b][k] * d * d;
      }
      units[k] = {n / total, m, std::max(std::sqrt(v / n), kSmallestSd)};
    }
    if (std::abs(log_likelihood - previous) <= kConvergence * std::abs(log_likelihood)) break;
    previous = log_likelihood;
  }
  std::sort(units.begin(), units.end(), [](const SlopeUnit& a, const SlopeUnit& b) { return a.mean < b.mean; });
  return units;
}

std::optional<double> cliff_threshold(const std::array<SlopeUnit, 4>& units) {
  const SlopeUnit& steep = units[2];
  const SlopeUnit& cliff = units[3];
  for (int tenth = static_cast<int>(std::ceil(steep.mean * 10)); tenth <= 900; ++tenth) {
    const double angle = tenth / 10.0;
    if (density(cliff, angle) > density(steep, angle)) return angle;
  }
  return std::nullopt;
}

Grid<float> source_mask(const Grid<float>& slopes, double threshold_deg, const Grid<int>& lithology,
                        const std::set<int>& classes) {
  require_same_grid(slopes.spec(), lithology.spec(), "slope and lithology");
  Grid<float> mask(slopes.spec(), 0.0f);
  for (std::size_t cell = 0; cell < slopes.size(); ++cell) {
    const bool steep = slopes.is_valid(cell) && slopes[cell] >= threshold_deg;
    const bool rock = classes.empty() || classes.count(lithology[cell]) > 0;
    if (steep && rock) mask[cell] = 1.0f;
  }
  return mask;
}

}  // namespace talus
