// FixedPointSums: a sum per grid cell kept as an integer number of quanta (docs/architecture.md section
// 2, "Statistical maps": energy lost by friction and by ground deformation). Each added value
// is rounded to the nearest quantum once, then sums are int64 additions, which are associative:
// merged sums are bit-exact in any order, unlike floating-point sums. Overflow is guarded: a
// value or a sum beyond the int64 range saturates and sets saturated(); for values of one sign
// the saturated result is still order independent.
#pragma once

#include <cstddef>
#include <cstdint>

#include "talus/core/byte_stream.hpp"
#include "talus/hazard/zeroed_vector.hpp"

namespace talus {

class FixedPointSums {
 public:
  // quantum: the value of one integer unit, in the unit of the added values (> 0).
  FixedPointSums(std::size_t cell_count, double quantum);

  void add(std::size_t cell, double value);    // value rounded to the nearest quantum
  // Adds every cell of `other` (same cell count and quantum) into this one.
  void merge(const FixedPointSums& other);
  // For MPI ranks (core/byte_stream.hpp): the non-zero cells and the saturation flag; read()
  // into an all-zero one of the same quantum.
  void write(ByteWriter& out) const;
  void read(ByteReader& in);

  double total(std::size_t cell) const { return static_cast<double>(sums_[cell]) * quantum_; }
  std::int64_t quanta(std::size_t cell) const { return sums_[cell]; }
  double quantum() const { return quantum_; }
  std::size_t size() const { return sums_.size(); }
  // True once a value was not finite or a value or a sum left the int64 range of quanta.
  bool saturated() const { return saturated_; }

 private:
  std::int64_t checked_sum(std::int64_t a, std::int64_t b);

  ZeroedVector<std::int64_t> sums_;
  double quantum_;
  bool saturated_ = false;
};

}  // namespace talus
