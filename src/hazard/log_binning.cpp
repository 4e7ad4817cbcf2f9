// LogBinning: logarithmic bin edges and exact bin lookup for the quantile estimator
// (docs/architecture.md section 2, "Statistical maps").
#include "talus/hazard/log_binning.hpp"

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace talus {

namespace {
// log2 of a positive normal double to within 0.008: the exponent bits plus a quadratic in the
// mantissa m in [1, 2), x (1.3466 - 0.3466 x) with x = m - 1. Only a first guess of the bin.
double approximate_log2(double value) {
  const auto bits = std::bit_cast<std::uint64_t>(value);
  const auto exponent = static_cast<int>(bits >> 52) - 1023;
  const double x = std::bit_cast<double>((bits & 0x000fffffffffffffULL) | 0x3ff0000000000000ULL) - 1.0;
  return exponent + x * (1.3466 - 0.3466 * x);
}
}  // namespace

LogBinning::LogBinning(double min, double max, int bins_per_decade)
    : bins_per_decade_(bins_per_decade), ratio_(std::pow(10.0, 1.0 / bins_per_decade)),
      log2_min_(std::log2(min)), bins_per_log2_(bins_per_decade * std::log10(2.0)) {
  if (!(min >= std::numeric_limits<double>::min()) || !(max > min) || !std::isfinite(max) || bins_per_decade < 1) {
    throw std::invalid_argument("LogBinning: needs 0 < min < max (normal numbers) and at least one bin per decade");
  }
  const double decades = std::log10(max / min);
  const int bins = static_cast<int>(std::ceil(decades * bins_per_decade - 1e-9));
  edges_.reserve(static_cast<std::size_t>(bins) + 1);
  for (int k = 0; k <= bins; ++k) edges_.push_back(min * std::pow(10.0, static_cast<double>(k) / bins_per_decade));
}

int LogBinning::bin_of(double value) const {
  if (!(value >= edges_.front())) return underflow;
  if (value >= edges_.back()) return overflow();
  // A guess from an approximate logarithm, then corrected against the edges themselves.
  const int last = bin_count() - 1;
  int bin = std::clamp(static_cast<int>((approximate_log2(value) - log2_min_) * bins_per_log2_), 0, last);
  while (value < lower(bin)) --bin;
  while (value >= upper(bin)) ++bin;
  return bin;
}

}  // namespace talus
