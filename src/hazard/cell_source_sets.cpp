// CellSourceSets: per-cell sets of release sources as sorted intervals, and their exact union
// (docs/hazard-statistics.md, "How `source_count` is gathered").
#include "talus/hazard/cell_source_sets.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace talus {
namespace {

// True when `next` (first >= previous.first) overlaps `previous` or starts right after it.
bool joins(const SourceInterval& previous, const SourceInterval& next) {
  return static_cast<std::uint64_t>(previous.last) + 1 >= next.first;
}

// The union of two sets, both sorted, disjoint and non-adjacent, as one such set.
std::vector<SourceInterval> united(const std::vector<SourceInterval>& a, const std::vector<SourceInterval>& b) {
  std::vector<SourceInterval> out;
  out.reserve(a.size() + b.size());
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    const bool from_a = j == b.size() || (i < a.size() && a[i].first <= b[j].first);
    const SourceInterval next = from_a ? a[i++] : b[j++];
    if (!out.empty() && joins(out.back(), next)) {
      out.back().last = std::max(out.back().last, next.last);
    } else {
      out.push_back(next);
    }
  }
  return out;
}

}  // namespace

CellSourceSets::CellSourceSets(std::size_t cell_count) : slot_(cell_count) {   // every slot starts at no_set (0)
  if (cell_count >= std::numeric_limits<std::uint32_t>::max()) {
    throw std::invalid_argument("CellSourceSets: too many cells for 32-bit cell indices");
  }
}

std::vector<SourceInterval>& CellSourceSets::set(std::size_t cell) {
  const std::uint32_t slot = slot_[cell];
  if (slot != no_set) return sets_[slot - 1];
  sets_.emplace_back();
  cells_.push_back(static_cast<std::uint32_t>(cell));
  slot_[cell] = static_cast<std::uint32_t>(sets_.size());
  return sets_.back();
}

void CellSourceSets::add(std::size_t cell, std::uint32_t source) {
  std::vector<SourceInterval>& s = set(cell);
  const SourceInterval single{source, source};
  if (s.empty() || !joins(s.back(), single)) {
    s.push_back(single);
    return;
  }
  if (source >= s.back().first) {
    s.back().last = std::max(s.back().last, source);
    return;
  }
  // Out of order: the first interval that ends at most one source before `source`.
  auto it = std::lower_bound(s.begin(), s.end(), source, [](const SourceInterval& interval, std::uint32_t value) {
    return !joins(interval, SourceInterval{value, value});
  });
  if (source >= it->first) {
    it->last = std::max(it->last, source);
    const auto next = it + 1;
    if (next != s.end() && joins(*it, *next)) {
      it->last = next->last;
      s.erase(next);
    }
  } else if (static_cast<std::uint64_t>(source) + 1 == it->first) {
    it->first = source;   // the interval before ends at least two sources earlier
  } else {
    s.insert(it, single);
  }
}

void CellSourceSets::merge(const CellSourceSets& other) {
  if (other.size() != size()) throw std::invalid_argument("CellSourceSets::merge: different cell counts");
  if (&other == this) return;   // a set united with itself is itself
  for (std::size_t i = 0; i < other.sets_.size(); ++i) {
    const std::size_t cell = other.cells_[i];
    if (slot_[cell] == no_set) {
      set(cell) = other.sets_[i];
    } else {
      std::vector<SourceInterval>& mine = sets_[slot_[cell] - 1];
      mine = united(mine, other.sets_[i]);
    }
  }
}

std::uint64_t CellSourceSets::count(std::size_t cell) const {
  std::uint64_t n = 0;
  for (const SourceInterval& interval : intervals(cell)) {
    n += static_cast<std::uint64_t>(interval.last) - interval.first + 1;
  }
  return n;
}

std::span<const SourceInterval> CellSourceSets::intervals(std::size_t cell) const {
  const std::uint32_t slot = slot_[cell];
  if (slot == no_set) return {};
  return sets_[slot - 1];
}

void CellSourceSets::write(ByteWriter& out) const {
  out.put<std::uint64_t>(size());
  out.put<std::uint64_t>(sets_.size());
  for (std::size_t i = 0; i < sets_.size(); ++i) {
    out.put(cells_[i]);
    out.put_vector(sets_[i]);
  }
}

void CellSourceSets::read(ByteReader& in) {
  if (in.get_cell_count() != size() || !sets_.empty()) throw std::runtime_error("rank message: source sets of another grid");
  const std::uint64_t reached = in.get<std::uint64_t>();
  for (std::uint64_t i = 0; i < reached; ++i) {
    const auto cell = in.get_cell<std::uint32_t>();
    if (cell >= size() || slot_[cell] != no_set) throw std::runtime_error("rank message: a cell outside the grid");
    in.get_vector(set(cell));
  }
}

}  // namespace talus
