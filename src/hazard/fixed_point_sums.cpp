// FixedPointSums: rounding to quanta and overflow-guarded int64 sums (docs/architecture.md section 2,
// "Statistical maps": energy lost by friction and by ground deformation).
#include "talus/hazard/fixed_point_sums.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace talus {

namespace {
constexpr std::int64_t kLargest = std::numeric_limits<std::int64_t>::max();
constexpr std::int64_t kSmallest = std::numeric_limits<std::int64_t>::min();
constexpr double kRange = 9223372036854775808.0;   // 2^63: |quanta| below it fit in int64
}  // namespace

FixedPointSums::FixedPointSums(std::size_t cell_count, double quantum) : sums_(cell_count), quantum_(quantum) {
  if (!(quantum > 0) || !std::isfinite(quantum)) throw std::invalid_argument("FixedPointSums: the quantum must be > 0");
}

std::int64_t FixedPointSums::checked_sum(std::int64_t a, std::int64_t b) {
  if (b > 0 && a > kLargest - b) {
    saturated_ = true;
    return kLargest;
  }
  if (b < 0 && a < kSmallest - b) {
    saturated_ = true;
    return kSmallest;
  }
  return a + b;
}

void FixedPointSums::add(std::size_t cell, double value) {
  const double scaled = value / quantum_;
  std::int64_t quanta = 0;
  if (std::abs(scaled) < kRange) {
    quanta = std::llround(scaled);
  } else {
    saturated_ = true;
    if (!std::isnan(scaled)) quanta = scaled > 0 ? kLargest : kSmallest;
  }
  sums_[cell] = checked_sum(sums_[cell], quanta);
}

void FixedPointSums::merge(const FixedPointSums& other) {
  if (other.size() != size() || other.quantum_ != quantum_) {
    throw std::invalid_argument("FixedPointSums::merge: different cell counts or quanta");
  }
  saturated_ = saturated_ || other.saturated_;
  // Cells without sums in `other` are only read: untouched zero pages stay untouched.
  for (std::size_t i = 0; i < sums_.size(); ++i) {
    if (other.sums_[i] != 0) sums_[i] = checked_sum(sums_[i], other.sums_[i]);
  }
}

void FixedPointSums::write(ByteWriter& out) const {
  out.put<std::uint8_t>(saturated_ ? 1 : 0);
  out.put_sparse(sums_);
}

void FixedPointSums::read(ByteReader& in) {
  saturated_ = in.get<std::uint8_t>() != 0;
  in.get_sparse(sums_);
}

}  // namespace talus
