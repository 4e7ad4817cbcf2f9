// The order of a substep's evaluations (evaluation_order.hpp): each force only after the
// densities it reads, within its thread's part, and every other force left waiting.
#include "talus/mudflow/evaluation_order.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace talus {
namespace {

// Particles on a line: the neighbours of i are the particles within 1 to 12 places of it (the
// reach varies with i, as the smoothing radii do), as a pair search over particles sorted along
// the flow would give. With 5 to 8 parts a part is shorter than the longest reach, as in a
// substep of an adaptive run that evaluates a few particles spread over the flow.
struct LineOfParticles {
  static constexpr std::uint32_t kCount = 61;
  static constexpr int kLongestReach = 12;

  static int reach(std::uint32_t i) { return 1 + static_cast<int>(i * 7 % kLongestReach); }
  static std::vector<std::uint32_t> neighbours(std::uint32_t i) {
    std::vector<std::uint32_t> out;
    for (int d = -reach(i); d <= reach(i); ++d) {
      const auto j = static_cast<std::int64_t>(i) + d;
      if (d != 0 && j >= 0 && j < kCount) out.push_back(static_cast<std::uint32_t>(j));
    }
    return out;
  }
  // A substep's list: the particles whose steps end now, not one in five nor the last six.
  static std::vector<std::uint32_t> listed() {
    std::vector<std::uint32_t> list;
    for (std::uint32_t i = 0; i + 6 < kCount; ++i) {
      if (i % 5 != 1) list.push_back(i);
    }
    return list;
  }
};

struct Trace {
  std::vector<int> densities = std::vector<int>(LineOfParticles::kCount, 0);  // calls per particle
  std::vector<int> forces = std::vector<int>(LineOfParticles::kCount, 0);
  std::vector<std::size_t> part_of = std::vector<std::size_t>(LineOfParticles::kCount, 0);
  std::vector<bool> listed = std::vector<bool>(LineOfParticles::kCount, false);
  std::size_t waited = 0;
  bool interleaved = false;  // some force of a part came before the part's last density
};

// Runs the parts one after the other, as a thread each would, then the waiting forces, and
// checks that every force read only densities that its own part had already computed.
Trace run_in_parts(std::size_t parts) {
  const std::vector<std::uint32_t> list = LineOfParticles::listed();
  Trace trace;
  for (std::size_t part = 0; part < parts; ++part) {
    for (std::size_t p = list.size() * part / parts; p < list.size() * (part + 1) / parts; ++p) {
      trace.part_of[list[p]] = part;
      trace.listed[list[p]] = true;
    }
  }
  std::vector<std::vector<std::uint32_t>> waiting(parts);
  std::vector<NeighbourSpan> spans;
  for (std::size_t part = 0; part < parts; ++part) {
    const std::size_t begin = list.size() * part / parts, end = list.size() * (part + 1) / parts;
    std::size_t densities_done = 0;
    const auto density = [&](std::uint32_t i) {
      ++trace.densities[i];
      ++densities_done;
      NeighbourSpan span{i, i};
      for (const std::uint32_t j : LineOfParticles::neighbours(i)) {
        span.lowest = std::min(span.lowest, j);
        span.highest = std::max(span.highest, j);
      }
      return span;
    };
    const auto forces = [&](std::uint32_t k) {
      ++trace.forces[k];
      if (densities_done < end - begin) trace.interleaved = true;
      EXPECT_EQ(trace.densities[k], 1) << "forces of " << k << " before its own density";
      for (const std::uint32_t j : LineOfParticles::neighbours(k)) {
        if (!trace.listed[j]) continue;  // not evaluated in this substep: nothing to wait for
        EXPECT_EQ(trace.part_of[j], part) << "forces of " << k << " read " << j << " of another part";
        EXPECT_EQ(trace.densities[j], 1) << "forces of " << k << " before the density of " << j;
      }
    };
    evaluate_part_in_order(list, begin, end, density, forces, spans, waiting[part]);
  }
  for (const std::vector<std::uint32_t>& part_waiting : waiting) {
    for (const std::uint32_t k : part_waiting) ++trace.forces[k];
    trace.waited += part_waiting.size();
  }
  return trace;
}

TEST(EvaluationOrder, EachForceFollowsTheDensitiesItReadsInItsOwnPart) {
  for (std::size_t parts = 1; parts <= 8; ++parts) {
    SCOPED_TRACE(parts);
    const Trace trace = run_in_parts(parts);
    for (std::uint32_t i = 0; i < LineOfParticles::kCount; ++i) {
      const int expected = trace.listed[i] ? 1 : 0;
      EXPECT_EQ(trace.densities[i], expected) << i;
      EXPECT_EQ(trace.forces[i], expected) << i;
    }
    EXPECT_TRUE(trace.interleaved);
    // Only the particles within reach of a boundary between parts wait.
    EXPECT_LE(trace.waited, (parts - 1) * 2 * LineOfParticles::kLongestReach);
    if (parts == 1) {
      EXPECT_EQ(trace.waited, 0u);
    }
  }
}

}  // namespace
}  // namespace talus
