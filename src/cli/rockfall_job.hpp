// The work of `talus rockfall` as one library call (issue 19), as GDAL's utilities are functions
// with a thin program around them: the subcommand, `talus study` and every MPI rank call it.
#pragma once

#include "job_output.hpp"
#include "parameter_table.hpp"
#include "process_ranks.hpp"
#include "rockfall_parameters.hpp"

namespace talus::cli {

// Resolves and checks the parameters (`table` over `o`, flags pinned), reads the scene, runs the
// trajectories and commits the layer set, trajectories.gpkg and run.json to o.out; throws
// InputError, NumericalFailure or Cancelled with nothing written. Among MPI ranks, each rank
// simulates its share of the sources (rockfall_shares.hpp) and rank 0 joins them and writes:
// the same files as one process, bit for bit.
void rockfall_job(RockfallOptions& o, ParameterTable& table, const JobOutput& output,
                  const ProcessRanks& ranks = single_process());

}  // namespace talus::cli
