// Contiguous parts of the particles, one per thread (OpenMP), for the passes of the mud flow that
// must give the same result for any thread count: the pair search's sort and the order of a
// substep's evaluation.
#pragma once

#include <cstddef>

#include <omp.h>

namespace talus {

// body(part, first, last) for each of `parts` contiguous parts [first, last) of the items
// 0..n-1, on up to `parts` threads. A part's bounds depend only on n and parts, never on the
// threads the region gets, so passes over the same parts agree.
template <class Body>
void for_each_part(std::size_t n, std::size_t parts, Body&& body) {
#pragma omp parallel num_threads(static_cast<int>(parts)) if (parts > 1)
  {
    const auto team = static_cast<std::size_t>(omp_get_num_threads());
    for (auto part = static_cast<std::size_t>(omp_get_thread_num()); part < parts; part += team) {
      body(part, n * part / parts, n * (part + 1) / parts);
    }
  }
}

}  // namespace talus
