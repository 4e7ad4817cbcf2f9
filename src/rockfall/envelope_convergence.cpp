// The convergence measure of the Monte Carlo maps and the batch rule of `--runs auto`
// (envelope_convergence.hpp; docs/hazard-statistics.md, "Convergence").
#include "talus/rockfall/envelope_convergence.hpp"

#include <algorithm>
#include <cmath>

namespace talus {
namespace {

// The whole run's maps are sums of per-run values: reach in 2^-40 (a cell reached once in a
// million runs is 2^20 quanta), energy in millijoules per run.
constexpr double kReachQuantum = 0x1.0p-40;
constexpr double kEnergyQuantum = 1e-3;  // J

}  // namespace

// Sort by cell, then add up each run of equal cells into its first.
Envelope envelope_of(std::vector<EnvelopeCell> cells) {
  std::sort(cells.begin(), cells.end(), [](const EnvelopeCell& a, const EnvelopeCell& b) { return a.cell < b.cell; });
  Envelope out;
  for (const EnvelopeCell& c : cells) {
    if (!out.empty() && out.back().cell == c.cell) {
      out.back().passages += c.passages;
      out.back().energy += c.energy;
    } else {
      out.push_back(c);
    }
  }
  return out;
}

// A merge of the two sorted lists, equal cells added.
Envelope envelope_sum(const Envelope& a, const Envelope& b) {
  Envelope out;
  out.reserve(std::max(a.size(), b.size()));
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i].cell < b[j].cell)) {
      out.push_back(a[i++]);
    } else if (i == a.size() || b[j].cell < a[i].cell) {
      out.push_back(b[j++]);
    } else {
      out.push_back({a[i].cell, a[i].passages + b[j].passages, a[i].energy + b[j].energy});
      ++i;
      ++j;
    }
  }
  return out;
}

// f = P / n, g = W / n.
EnvelopeField per_run(const Envelope& envelope, std::uint64_t runs) {
  EnvelopeField field;
  field.reserve(envelope.size());
  const double n = static_cast<double>(std::max<std::uint64_t>(runs, 1));
  for (const EnvelopeCell& c : envelope) {
    field.push_back({c.cell, static_cast<double>(c.passages) / n, static_cast<double>(c.energy) / n});
  }
  return field;
}

// One pass over both sorted lists, the sums in cell order (so that the same maps give the same
// bits whatever order their trajectories were recorded in).
EnvelopeChange envelope_change(const EnvelopeField& before, const EnvelopeField& after) {
  EnvelopeChange change{before.size(), after.size(), 0.0, 0.0};
  double reach_difference = 0, reach_total = 0, energy_difference = 0, energy_total = 0;
  std::size_t i = 0, j = 0;
  while (i < before.size() || j < after.size()) {
    FieldCell b, a;
    if (j == after.size() || (i < before.size() && before[i].cell < after[j].cell)) {
      b = before[i++];
    } else if (i == before.size() || after[j].cell < before[i].cell) {
      a = after[j++];
    } else {
      b = before[i++];
      a = after[j++];
    }
    reach_difference += std::abs(a.reach - b.reach);
    reach_total += a.reach;
    energy_difference += std::abs(a.energy - b.energy);
    energy_total += a.energy;
  }
  if (reach_total > 0) change.reach_change = reach_difference / reach_total;
  if (energy_total > 0) change.energy_change = energy_difference / energy_total;
  return change;
}

bool envelope_converged(const EnvelopeChange& change, double tolerance) {
  return change.reach_change < tolerance && change.energy_change < tolerance;
}

std::uint64_t auto_run_limit(const ConvergenceParameters& parameters) {
  std::uint64_t limit = parameters.min_runs;
  while (limit <= parameters.max_runs / 2) limit *= 2;
  return limit;
}

// change(n) = c (n / runs)^-1/2 falls below the tolerance at n = runs (c / tolerance)^2.
std::uint64_t suggested_runs(std::uint64_t runs, const EnvelopeChange& change, double tolerance) {
  if (envelope_converged(change, tolerance)) return runs;
  const double ratio = std::max(change.reach_change, change.energy_change) / tolerance;
  const auto tens = static_cast<std::uint64_t>(std::ceil(static_cast<double>(runs) * ratio * ratio / 10.0));
  return std::max(runs + 1, 10 * tens);
}

EnvelopeGrid::EnvelopeGrid(std::size_t cell_count)
    : reach_(cell_count, kReachQuantum), energy_(cell_count, kEnergyQuantum) {}

void EnvelopeGrid::add(const EnvelopeField& field) {
  for (const FieldCell& c : field) {
    reach_.add(c.cell, c.reach);
    energy_.add(c.cell, c.energy);
  }
}

void EnvelopeGrid::merge(const EnvelopeGrid& other) {
  reach_.merge(other.reach_);
  energy_.merge(other.energy_);
}

void EnvelopeGrid::write(ByteWriter& out) const {
  reach_.write(out);
  energy_.write(out);
}

void EnvelopeGrid::read(ByteReader& in) {
  reach_.read(in);
  energy_.read(in);
}

EnvelopeField EnvelopeGrid::field() const {
  EnvelopeField out;
  for (std::size_t cell = 0; cell < reach_.size(); ++cell) {
    if (reach_.quanta(cell) != 0) out.push_back({static_cast<std::uint32_t>(cell), reach_.total(cell), energy_.total(cell)});
  }
  return out;
}

}  // namespace talus
