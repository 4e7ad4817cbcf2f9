// Convergence of the Monte Carlo maps (issue 17, item 2; docs/hazard-statistics.md,
// "Convergence"): the paper's "model no more than a scene needs" (section 1) applied to the
// number of runs of paper 3.4. After n runs, the envelope of a source is, per DEM cell, the
// passages P_n(c) and the sum W_n(c) of the passages' largest kinetic energies there; per run,
// f_n = P_n / n is the cell's reach probability and g_n = W_n / n the energy brought into it.
// Doubling the runs from n/2 to n changes them by
//   reach change  = sum_c |f_n/2(c) - f_n(c)| / sum_c f_n(c)
//   energy change = sum_c |g_n/2(c) - g_n(c)| / sum_c g_n(c)
// (L1 changes of the two maps, relative to their totals: 0 when nothing moves, 1 when half the
// runs reached nothing the others did), and the envelope has converged when both are below a
// tolerance. Both are Monte Carlo estimates' differences, falling as 1 / sqrt(n). `--runs auto`
// adds runs per source in batches that double its runs from min_runs until its own envelope has
// converged or the next doubling would pass max_runs; the decision depends on that source's
// trajectories only, so the layers stay bit-identical for any thread count. Every source's
// change below the tolerance bounds the change of their sum (the whole map) below it too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "talus/hazard/fixed_point_sums.hpp"

namespace talus {

// [run] parameters of the convergence test and of `--runs auto`.
struct ConvergenceParameters {
  double tolerance = 0.05;        // - : largest reach change and energy change of a converged envelope
  std::uint64_t min_runs = 20;    // runs per source before the first test (auto); its first batch
  std::uint64_t max_runs = 1280;  // most runs per source (auto)
};

// One cell of a source's envelope: its index in the DEM grid (row-major), the passages through
// it and the sum of their largest kinetic energies in it.
struct EnvelopeCell {
  std::uint32_t cell = 0;
  std::uint64_t passages = 0;
  std::uint64_t energy = 0;  // J, rounded to whole joules per passage (so that sums are exact)
};

// The cells some trajectories crossed, sorted by cell, each once.
using Envelope = std::vector<EnvelopeCell>;

// One cell of the per-run maps: reach probability f and energy brought per run g.
struct FieldCell {
  std::uint32_t cell = 0;
  double reach = 0;   // passages per run
  double energy = 0;  // J per run
};
using EnvelopeField = std::vector<FieldCell>;  // sorted by cell

// The change of the maps from `before` (n/2 runs) to `after` (n runs), by the formulas above.
struct EnvelopeChange {
  std::uint64_t reached_before = 0;  // cells with a passage
  std::uint64_t reached_after = 0;   // cells with a passage
  double reach_change = 0;           // - (0 when nothing was reached)
  double energy_change = 0;          // - (0 when every energy is 0)
};

// Sorts the cells and joins those of equal index, adding their passages and energies.
Envelope envelope_of(std::vector<EnvelopeCell> cells);

// The sum of two envelopes (of disjoint sets of runs of one source).
Envelope envelope_sum(const Envelope& a, const Envelope& b);

// The per-run maps of an envelope of `runs` runs.
EnvelopeField per_run(const Envelope& envelope, std::uint64_t runs);

// The change from `before` to `after`, summed in cell order.
EnvelopeChange envelope_change(const EnvelopeField& before, const EnvelopeField& after);

// Both changes below the tolerance.
bool envelope_converged(const EnvelopeChange& change, double tolerance);

// The most runs a source gets in auto mode: the largest min_runs x 2^k not above max_runs.
std::uint64_t auto_run_limit(const ConvergenceParameters& parameters);

// The runs per source the maps would need to meet the tolerance, from their change over the
// doubling that ended at `runs`, assuming the change falls as 1 / sqrt(runs), rounded up to a
// multiple of 10; `runs` itself when already converged.
std::uint64_t suggested_runs(std::uint64_t runs, const EnvelopeChange& change, double tolerance);

// The sum of many sources' per-run maps on a grid of `cell_count` cells (the whole run's maps),
// in fixed point, so that it is the same whatever order the sources are added in.
class EnvelopeGrid {
 public:
  explicit EnvelopeGrid(std::size_t cell_count);
  void add(const EnvelopeField& field);
  // The sums of another grid's sources (MPI ranks, issue 19), exact in any order.
  void merge(const EnvelopeGrid& other);
  void write(ByteWriter& out) const;
  void read(ByteReader& in);
  EnvelopeField field() const;

 private:
  FixedPointSums reach_, energy_;
};

}  // namespace talus
