// Plain bytes for the statistics that MPI ranks send to rank 0 (issue 19, item 6): numbers in
// the machine's own layout (every rank of one job runs the same build on the same kind of
// machine), vectors with their length, and per-cell arrays as the list of their non-zero cells,
// since a rank's trajectories reach only a part of the DEM.
#pragma once

#include <cstdint>
#include <cstring>
#include <span>
#include <stdexcept>
#include <type_traits>
#include <vector>

#include "talus/core/grid_spec.hpp"

namespace talus {

class ByteWriter {
 public:
  template <class T>
  void put(T value) {
    static_assert(std::is_trivially_copyable_v<T>);
    const std::size_t at = bytes_.size();
    bytes_.resize(at + sizeof(T));
    std::memcpy(bytes_.data() + at, &value, sizeof(T));
  }
  template <class T, class A>
  void put_vector(const std::vector<T, A>& values) {
    put<std::uint64_t>(values.size());
    for (const T& v : values) put(v);
  }
  // The non-zero entries of a per-cell array, as (cell, value) pairs.
  template <class T, class A>
  void put_sparse(const std::vector<T, A>& cells) {
    std::uint64_t non_zero = 0;
    for (const T& v : cells) non_zero += v != T{} ? 1 : 0;
    put<std::uint64_t>(cells.size());
    put<std::uint64_t>(non_zero);
    for (std::size_t i = 0; i < cells.size(); ++i) {
      if (cells[i] != T{}) {
        put<std::uint64_t>(i);
        put(cells[i]);
      }
    }
  }
  const std::vector<std::uint8_t>& bytes() const { return bytes_; }
  std::vector<std::uint8_t> take() { return std::move(bytes_); }

 private:
  std::vector<std::uint8_t> bytes_;
};

// Reads what a ByteWriter wrote, in the same order; a short or inconsistent message throws
// std::runtime_error (a fault of the transfer, not of the user's input).
class ByteReader {
 public:
  explicit ByteReader(std::span<const std::uint8_t> bytes) : bytes_(bytes) {}
  // Reads a tile's message into the whole grid's arrays (issue 19, item 4): its per-cell arrays
  // cover the window `tile` (GridSpec), and their cells are renumbered on the whole grid.
  ByteReader(std::span<const std::uint8_t> bytes, const GridSpec& tile) : bytes_(bytes), tile_(tile) {}

  // The cell count a per-cell array was written with; from a tile, its whole grid's.
  std::uint64_t get_cell_count() {
    const auto n = get<std::uint64_t>();
    if (!tile_.is_window()) return n;
    if (n != tile_.cell_count()) throw std::runtime_error("rank message: a per-cell array of another tile");
    return tile_.whole().cell_count();
  }
  // A cell's index; from a tile, on its whole grid.
  template <class T>
  T get_cell() {
    const T cell = get<T>();
    if (!tile_.is_window()) return cell;
    if (cell >= tile_.cell_count()) throw std::runtime_error("rank message: a cell outside the tile");
    return static_cast<T>(tile_.whole_index(cell));
  }
  template <class T>
  T get() {
    static_assert(std::is_trivially_copyable_v<T>);
    if (bytes_.size() - offset_ < sizeof(T)) throw std::runtime_error("rank message: shorter than its contents");
    T value;
    std::memcpy(&value, bytes_.data() + offset_, sizeof(T));
    offset_ += sizeof(T);
    return value;
  }
  template <class T, class A>
  void get_vector(std::vector<T, A>& values) {
    const std::uint64_t n = get<std::uint64_t>();
    if (n > (bytes_.size() - offset_) / sizeof(T)) throw std::runtime_error("rank message: shorter than its contents");
    values.resize(n);
    for (T& v : values) v = get<T>();
  }
  // Into an array of the writer's size, whose cells are all zero.
  template <class T, class A>
  void get_sparse(std::vector<T, A>& cells) {
    if (get_cell_count() != cells.size()) throw std::runtime_error("rank message: a per-cell array of another grid");
    const std::uint64_t non_zero = get<std::uint64_t>();
    for (std::uint64_t k = 0; k < non_zero; ++k) {
      const std::uint64_t i = get_cell<std::uint64_t>();
      if (i >= cells.size()) throw std::runtime_error("rank message: a cell outside the grid");
      cells[i] = get<T>();
    }
  }
  bool at_end() const { return offset_ == bytes_.size(); }

 private:
  std::span<const std::uint8_t> bytes_;
  std::size_t offset_ = 0;
  GridSpec tile_;  // whole unless reading a tile's message
};

}  // namespace talus
