// Tests of the exact pair search over radius classes (paper 4.1 neighbour search; pair_search.hpp).
#include "talus/mudflow/pair_search.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <span>
#include <vector>

#include <gtest/gtest.h>

namespace talus {
namespace {

// The pairs of particle i by brute force: j != i with r < max(R_i, R_j), in index order.
std::vector<std::uint32_t> brute_force_pairs(const ParticleSet& p, const std::vector<double>& radii, std::size_t i) {
  std::vector<std::uint32_t> pairs;
  for (std::uint32_t j = 0; j < p.size(); ++j) {
    const double r = std::hypot(p.x[i] - p.x[j], p.y[i] - p.y[j]);
    if (j != i && r < std::max(radii[i], radii[j])) pairs.push_back(j);
  }
  return pairs;
}

std::vector<std::uint32_t> found_pairs(const PairSearch& search, const ParticleSet& p, const std::vector<double>& radii,
                                       std::size_t i) {
  std::vector<std::uint32_t> pairs;
  for (const std::uint32_t s : search.find_pairs(p.x[i], p.y[i], radii[i], static_cast<std::uint32_t>(i))) {
    pairs.push_back(search.index(s));
  }
  return pairs;
}

// Every particle's pairs, sorted, compared with brute force (exactly, and without duplicates);
// returns how many there are.
std::size_t expect_brute_force_pairs(const PairSearch& search, const ParticleSet& p, const std::vector<double>& radii) {
  std::size_t pairs = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    std::vector<std::uint32_t> found = found_pairs(search, p, radii, i);
    std::sort(found.begin(), found.end());
    EXPECT_TRUE(std::adjacent_find(found.begin(), found.end()) == found.end()) << "duplicate pair of " << i;
    EXPECT_EQ(found, brute_force_pairs(p, radii, i)) << i;
    pairs += found.size();
  }
  return pairs;
}

// Adds `count` particles at random in a square of `side` (m), of 1-2 kg: a share
// `narrow_share` of radius 0.5 m, the others between 0.5 m and widest x 0.5 m.
void add_mixed_patch(std::mt19937& generator, int count, double side, double narrow_share, double widest,
                     ParticleSet& p, std::vector<double>& radii) {
  std::uniform_real_distribution<double> coordinate(0.0, side), unit(0.0, 1.0);
  for (int k = 0; k < count; ++k) {
    p.add(1.0 + unit(generator), {coordinate(generator), coordinate(generator), 0.0}, {0, 0, 0}, 0.5);
    radii.push_back(unit(generator) < narrow_share ? 0.5 : 0.5 * std::pow(widest, unit(generator)));
  }
}

TEST(PairSearch, FindsExactlyTheBruteForcePairsOverManyClasses) {
  // A dense patch of narrow particles, wider ones among them (radii 0.5 to 12 m: classes 0 to 5
  // with R0 = 0.5 m) and a few far-away stragglers that make the wide classes sparse.
  std::mt19937 generator(11);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  ParticleSet p;
  std::vector<double> radii;
  add_mixed_patch(generator, 600, 30.0, 0.8, 24.0, p, radii);
  for (int k = 0; k < 5; ++k) {
    p.add(1.0, {2000.0 * unit(generator), -1500.0 * unit(generator), 0.0}, {0, 0, 0}, 0.5);
    radii.push_back(6.0 * unit(generator) + 0.5);
  }
  PairSearch search;
  search.rebuild(p, radii, 0.5);
  const std::size_t pairs = expect_brute_force_pairs(search, p, radii);
  EXPECT_GT(pairs, 8000u);  // the scene has pairs through every class (9850, about 16 per particle)
}

TEST(PairSearch, FindsExactlyTheBruteForcePairsOnBinEdgesFarFromTheOrigin) {
  // Map coordinates (UTM-like, millions of metres) on a lattice whose lines fall on the bins'
  // edges (bins of R0 / 2 = 1 m from the lowest particle), and pairs exactly at r = R: rounding
  // must neither lose a pair nor add one.
  ParticleSet p;
  std::vector<double> radii;
  for (int a = 0; a < 24; ++a) {
    for (int b = 0; b < 24; ++b) {
      p.add(1.0, {654321.0 + 0.5 * a, 5123456.0 + 0.5 * b, 0.0}, {0, 0, 0}, 2.0);
      radii.push_back((a + b) % 7 == 0 ? 3.0 : 2.0);
    }
  }
  PairSearch search;
  search.rebuild(p, radii, 2.0);
  EXPECT_EQ(expect_brute_force_pairs(search, p, radii), 29184u);  // by brute force: about 51 per particle
}

TEST(PairSearch, SlotsCopyThePositionsRadiiAndMasses) {
  ParticleSet p;
  std::vector<double> radii;
  for (int k = 0; k < 50; ++k) {
    p.add(10.0 + k, {0.3 * k, 0.1 * k * k, 0.0}, {0, 0, 0}, 1.0);
    radii.push_back(1.0 + 0.1 * k);
  }
  PairSearch search;
  search.rebuild(p, radii, 1.0);
  const std::span<const std::uint32_t> slots = search.find_pairs(0.0, 0.0, 1000.0, 9999);  // reaches everyone
  ASSERT_EQ(slots.size(), p.size());
  for (const std::uint32_t s : slots) {
    const std::uint32_t i = search.index(s);
    EXPECT_EQ(search.x(s), p.x[i]);
    EXPECT_EQ(search.y(s), p.y[i]);
    EXPECT_EQ(search.radius(s), radii[i]);
    EXPECT_EQ(search.inverse_radius(s), 1.0 / radii[i]);
    EXPECT_EQ(search.mass(s), p.mass[i]);
  }
}

TEST(PairSearch, OrderDependsOnlyOnTheParticles) {
  // Two searches built from the same particles list every pair in the same order; a query far
  // outside every bin finds nothing.
  std::mt19937 generator(5);
  std::uniform_real_distribution<double> coordinate(0.0, 10.0), radius(0.4, 3.0);
  ParticleSet p;
  std::vector<double> radii;
  for (int k = 0; k < 300; ++k) {
    p.add(1.0, {coordinate(generator), coordinate(generator), 0.0}, {0, 0, 0}, 0.4);
    radii.push_back(radius(generator));
  }
  PairSearch first, second;
  first.rebuild(p, radii, 0.4);
  second.rebuild(p, radii, 0.4);
  for (std::size_t i = 0; i < p.size(); i += 7) {
    EXPECT_EQ(found_pairs(first, p, radii, i), found_pairs(second, p, radii, i));
  }
  EXPECT_TRUE(first.find_pairs(500.0, -500.0, 1.0, 0).empty());
}

TEST(PairSearch, SortingOnSeveralThreadsGivesTheSameSlots) {
  // The rebuild sorts contiguous parts of the particles on their own threads: for any number of
  // parts (more than the machine's cores included) every slot and every query's order of pairs
  // must be those of the one-thread sort.
  std::mt19937 generator(17);
  ParticleSet p;
  std::vector<double> radii;
  add_mixed_patch(generator, 1000, 20.0, 0.7, 6.0, p, radii);
  PairSearch single;
  single.rebuild(p, radii, 0.5, 1);
  for (const int threads : {2, 3, 7}) {
    PairSearch parallel;
    parallel.rebuild(p, radii, 0.5, threads);
    for (std::size_t i = 0; i < p.size(); ++i) {
      ASSERT_EQ(found_pairs(parallel, p, radii, i), found_pairs(single, p, radii, i)) << threads << " threads, " << i;
    }
    for (std::uint32_t s = 0; s < p.size(); ++s) {
      ASSERT_EQ(parallel.index(s), single.index(s)) << threads << " threads, slot " << s;
      ASSERT_EQ(parallel.mass(s), single.mass(s));
    }
  }
}

}  // namespace
}  // namespace talus
