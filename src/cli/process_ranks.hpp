// The processes one talus command runs in (issue 19, item 6): one, or the ranks of an MPI job
// (`mpirun -np N talus rockfall|study ...`, mpi_ranks.cpp). Every rank reads the same inputs
// and resolves the same parameters; rank 0 alone prints, shows progress and writes. A step that
// fails on one rank fails on every rank with the same error (together()), so that no rank waits
// forever for another and the exit code is the same everywhere.
#pragma once

#include <cstdint>
#include <functional>
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

// Runs `step` on this rank, then, when it threw on any rank, throws on every rank the error of
// the lowest rank that failed, as InputError, NumericalFailure, Cancelled or std::runtime_error.
void together(const ProcessRanks& ranks, const std::function<void()>& step);

}  // namespace talus::cli
