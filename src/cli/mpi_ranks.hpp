// The ranks of an MPI job as ProcessRanks (process_ranks.hpp; issue 19, item 6), for a talus
// built with MPI (CMake finds it; OpenMPI from Debian in scripts/setup.sh).
#pragma once

#include <memory>

#include "process_ranks.hpp"

namespace talus::cli {

// True when this process was started by mpirun or srun (their environment variables), so that a
// plain `talus ...` never starts MPI.
bool started_by_mpi_launcher();

// MPI initialised for this process (threads funnelled: only the main thread calls MPI) and
// finalised when the object goes.
std::unique_ptr<ProcessRanks> mpi_ranks(int& argc, char**& argv);

}  // namespace talus::cli
