// LogBinning: fixed logarithmic bins for the per-cell quantile estimator (docs/architecture.md section 2,
// "Statistical maps": 95th percentiles of kinetic energy and jump height over passages). Bin k
// covers [min 10^(k/b), min 10^((k+1)/b)) for b bins per decade; values below min (zero,
// negative, NaN) are underflow, values at or above the last edge are overflow. bin_of places a
// value exactly against the stored edges, so a value always lies inside its bin.
#pragma once

#include <vector>

namespace talus {

class LogBinning {
 public:
  static constexpr int underflow = -1;

  // min > 0, max > min, bins_per_decade >= 1; the last edge is the first min 10^(k/b) >= max.
  LogBinning(double min, double max, int bins_per_decade);

  int bin_count() const { return static_cast<int>(edges_.size()) - 1; }   // regular bins
  int overflow() const { return bin_count(); }
  // underflow, a regular bin 0 .. bin_count() - 1, or overflow().
  int bin_of(double value) const;
  double lower(int bin) const { return edges_[static_cast<std::size_t>(bin)]; }
  double upper(int bin) const { return edges_[static_cast<std::size_t>(bin) + 1]; }
  double min() const { return edges_.front(); }
  double max() const { return edges_.back(); }
  int bins_per_decade() const { return bins_per_decade_; }
  // Ratio of a bin's upper to lower edge: 10^(1/b).
  double bin_ratio() const { return ratio_; }

  bool operator==(const LogBinning& other) const {
    return bins_per_decade_ == other.bins_per_decade_ && edges_ == other.edges_;
  }

 private:
  std::vector<double> edges_;    // bin_count() + 1 increasing edges
  int bins_per_decade_;
  double ratio_;
  double log2_min_;
  double bins_per_log2_;         // bins per factor 2
};

}  // namespace talus
