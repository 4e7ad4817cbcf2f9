// LogHistogram: windowed logarithmic bin counts, exact merge and log-linear quantiles
// (docs/architecture.md section 2, "Statistical maps": 95th percentiles over passages).
#include "talus/hazard/log_histogram.hpp"

#include <algorithm>
#include <cmath>

#include "talus/hazard/cell_counts.hpp"

namespace talus {

namespace {
// Bins added on each side of a new value's bin when the window grows, so that a cell's window
// settles after a few passages instead of growing by one bin at a time.
constexpr int kSlack = 4;

void increment(std::uint32_t& count, std::uint32_t n) { count = CellCounts::saturating_sum(count, n); }
}  // namespace

void LogHistogram::cover(int first, int last) {
  if (counts_.empty()) {
    counts_.assign(static_cast<std::size_t>(last - first + 1), 0);
    first_ = first;
    return;
  }
  const int current_last = first_ + static_cast<int>(counts_.size()) - 1;
  if (first >= first_ && last <= current_last) return;
  first = std::min(first, first_);
  last = std::max(last, current_last);
  std::vector<std::uint32_t> widened(static_cast<std::size_t>(last - first + 1), 0);
  std::copy(counts_.begin(), counts_.end(), widened.begin() + (first_ - first));
  counts_.swap(widened);
  first_ = first;
}

void LogHistogram::add(double value, const LogBinning& binning) {
  const int bin = binning.bin_of(value);
  if (bin == LogBinning::underflow) {
    increment(underflow_, 1);
    return;
  }
  if (bin == binning.overflow()) {
    increment(overflow_, 1);
    return;
  }
  if (counts_.empty() || bin < first_ || bin >= first_ + static_cast<int>(counts_.size())) {
    cover(std::max(0, bin - kSlack), std::min(binning.bin_count() - 1, bin + kSlack));
  }
  increment(counts_[static_cast<std::size_t>(bin - first_)], 1);
}

void LogHistogram::merge(const LogHistogram& other) {
  increment(underflow_, other.underflow_);
  increment(overflow_, other.overflow_);
  if (other.counts_.empty()) return;
  cover(other.first_, other.first_ + static_cast<int>(other.counts_.size()) - 1);
  const std::size_t offset = static_cast<std::size_t>(other.first_ - first_);
  for (std::size_t i = 0; i < other.counts_.size(); ++i) increment(counts_[offset + i], other.counts_[i]);
}

std::uint64_t LogHistogram::count() const {
  std::uint64_t total = std::uint64_t{underflow_} + overflow_;
  for (const std::uint32_t c : counts_) total += c;
  return total;
}

double LogHistogram::quantile(double q, const LogBinning& binning) const {
  const std::uint64_t total = count();
  if (total == 0) return 0.0;
  const double rank = std::clamp(q, 0.0, 1.0) * static_cast<double>(total);
  // The wanted value is the k-th smallest, k = ceil(q N) in 1 .. N.
  const std::uint64_t k = std::clamp<std::uint64_t>(static_cast<std::uint64_t>(std::ceil(rank)), 1, total);
  std::uint64_t below = underflow_;
  if (k <= below) return 0.0;
  for (std::size_t i = 0; i < counts_.size(); ++i) {
    const std::uint32_t c = counts_[i];
    if (k <= below + c) {
      const int bin = first_ + static_cast<int>(i);
      const double fraction = std::clamp((rank - static_cast<double>(below)) / c, 0.0, 1.0);
      return binning.lower(bin) * std::pow(binning.bin_ratio(), fraction);
    }
    below += c;
  }
  return binning.max();
}

void LogHistogram::write(ByteWriter& out) const {
  out.put(first_);
  out.put(underflow_);
  out.put(overflow_);
  out.put_vector(counts_);
}

void LogHistogram::read(ByteReader& in) {
  first_ = in.get<std::int32_t>();
  underflow_ = in.get<std::uint32_t>();
  overflow_ = in.get<std::uint32_t>();
  in.get_vector(counts_);
}

}  // namespace talus
