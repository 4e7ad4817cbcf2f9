// LogHistogram: a bounded-memory estimate of one distribution over the fixed bins of a
// LogBinning (docs/architecture.md section 2, "Statistical maps": percentiles over passages without
// keeping every value). Counts live in a window of bins that grows to cover the values seen
// (never more than the binning's bins), plus separate underflow and overflow counts. Merging
// adds integer counts, so it is exact and order independent. quantile(q) finds the bin holding
// the ceil(q N)-th smallest value and interpolates log-linearly inside it: the estimate and that
// value lie in the same bin, so they differ by less than one bin ratio (10^(1/b)).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "talus/core/byte_stream.hpp"
#include "talus/hazard/log_binning.hpp"

namespace talus {

class LogHistogram {
 public:
  // Every call on one histogram must pass the same binning.
  void add(double value, const LogBinning& binning);
  void merge(const LogHistogram& other);
  // For MPI ranks (core/byte_stream.hpp); read() into an empty one.
  void write(ByteWriter& out) const;
  void read(ByteReader& in);
  std::uint64_t count() const;
  // q in [0, 1]; 0 for an empty histogram, 0 for ranks among underflow values, binning.max()
  // for ranks among overflow values.
  double quantile(double q, const LogBinning& binning) const;
  std::size_t memory_bytes() const { return sizeof(*this) + counts_.capacity() * sizeof(std::uint32_t); }

 private:
  // Widens the window to hold bins first .. last as well as those it holds now.
  void cover(int first, int last);

  std::vector<std::uint32_t> counts_;   // bins first_ .. first_ + counts_.size() - 1
  std::int32_t first_ = 0;
  std::uint32_t underflow_ = 0;
  std::uint32_t overflow_ = 0;
};

}  // namespace talus
