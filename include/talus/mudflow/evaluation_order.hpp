// The order in which a thread evaluates its part of a substep's particles (paper 4.1: the
// densities, then the forces, which read the neighbours' new densities; docs/mudflow.md
// "Threads"). Two passes over all the particles would read each neighbour list back long after
// it was written, from beyond the processor's second-level cache once the flow has a few
// thousand particles per thread. Here a particle's forces follow as soon as the densities they
// read are done: its neighbours lie a few rows of bins away in index order, so its list is
// still in the cache. A particle with a neighbour in another thread's part waits until every
// thread's densities are done. Only the moment each value is computed changes, never its inputs,
// so the results are those of the two passes, for any number of parts. Finding the spans costs
// about 4% more instructions, so the run keeps two passes for parts short enough for their lists
// to stay in the cache anyway (MudflowSettings::interleaved_particles).
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

namespace talus {

// The lowest and highest particle index among a particle's neighbours and itself: its forces
// read the densities of those listed in between.
struct NeighbourSpan {
  std::uint32_t lowest = 0;
  std::uint32_t highest = 0;
};

// The span of particle i with the neighbours in `neighbours` (each with an `index`).
template <class Neighbours>
NeighbourSpan neighbour_span(std::size_t i, const Neighbours& neighbours) {
  NeighbourSpan span{static_cast<std::uint32_t>(i), static_cast<std::uint32_t>(i)};
  for (const auto& neighbour : neighbours) {
    span.lowest = std::min(span.lowest, neighbour.index);
    span.highest = std::max(span.highest, neighbour.index);
  }
  return span;
}

// The particles list[begin, end) of a list in ascending index order, split into contiguous parts
// (one per thread). density(i) computes particle i's density and returns its NeighbourSpan;
// forces(k) computes particle k's forces. Every density of the part is computed in list order;
// every force whose listed neighbours all lie in the part is computed once their densities are;
// the others are appended to `waiting`, for the caller to compute after every part's densities.
// `spans` is scratch, reused between calls.
template <class Density, class Forces>
void evaluate_part_in_order(std::span<const std::uint32_t> list, std::size_t begin, std::size_t end,
                            Density&& density, Forces&& forces, std::vector<NeighbourSpan>& spans,
                            std::vector<std::uint32_t>& waiting) {
  waiting.clear();
  if (begin == end) return;
  spans.resize(end - begin);
  // Listed particles below `low` or above `high` belong to other parts.
  const std::uint32_t low = begin == 0 ? 0 : list[begin];
  const std::uint32_t high = end == list.size() ? std::numeric_limits<std::uint32_t>::max() : list[end - 1];
  const auto in_part = [&](const NeighbourSpan& span) { return span.lowest >= low && span.highest <= high; };
  std::size_t next = begin;  // the first particle of the part whose forces are neither done nor waiting
  for (std::size_t done = begin; done < end; ++done) {
    spans[done - begin] = density(list[done]);
    for (; next <= done; ++next) {
      const NeighbourSpan& span = spans[next - begin];
      if (!in_part(span)) {
        waiting.push_back(list[next]);
      } else if (span.highest <= list[done]) {
        forces(list[next]);
      } else {
        break;
      }
    }
  }
  for (; next < end; ++next) {
    if (in_part(spans[next - begin])) {
      forces(list[next]);
    } else {
      waiting.push_back(list[next]);
    }
  }
}

}  // namespace talus
