// The processes one talus command runs in (issue 19, item 6): one, or the ranks of an MPI job
// (`mpirun -np N talus rockfall|study ...`, mpi_ranks.cpp). Every rank reads the same inputs
// and resolves the same parameters; rank 0 alone prints, shows progress and writes. A step that
// fails on one rank fails on every rank with the same error (together()), so that no rank waits
// forever for another and the exit code is the same everywhere.
#pragma once

#include <cstdint>
#include <functional>
#include <utility>
#include <vector>

#include "talus/core/errors.hpp"

namespace talus::cli {

class ProcessRanks {
 public:
  virtual ~ProcessRanks() = default;
  virtual int rank() const = 0;
  virtual int size() const = 0;
  bool root() const { return rank() == 0; }
  // Every rank's bytes, in rank order, on rank 0; nothing on the other ranks.
  virtual std::vector<std::vector<std::uint8_t>> gather(const std::vector<std::uint8_t>& bytes) const = 0;
  // Rank 0's bytes, on every rank.
  virtual std::vector<std::uint8_t> broadcast(const std::vector<std::uint8_t>& bytes) const = 0;
};

// The command alone in its process.
const ProcessRanks& single_process();

// A numerical failure with its place in the whole work's order, the (source, run) of a
// trajectory: of several ranks' such failures the earliest is thrown, the one a single process
// would have met (monte_carlo.hpp).
class OrderedFailure : public NumericalFailure {
 public:
  OrderedFailure(const std::string& what, std::pair<std::uint64_t, std::uint64_t> where)
      : NumericalFailure(what), place(where) {}
  std::pair<std::uint64_t, std::uint64_t> place;
};

// Runs `step` on this rank, then, when it threw on any rank, throws on every rank the error of
// the lowest rank that failed (or the earliest OrderedFailure when every failure is one), as
// InputError, NumericalFailure, Cancelled or std::runtime_error.
void together(const ProcessRanks& ranks, const std::function<void()>& step);

}  // namespace talus::cli
