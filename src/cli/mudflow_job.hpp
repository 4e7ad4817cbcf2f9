// The work of `talus mudflow` as one library call (issue 19), as GDAL's utilities are functions
// with a thin program around them: the subcommand, `talus study` and every MPI rank call it.
#pragma once

#include "job_output.hpp"
#include "mudflow_parameters.hpp"
#include "parameter_table.hpp"

namespace talus::cli {

// Resolves and checks the parameters (`table` over `o`, flags pinned; `adaptive_given`: the
// adaptivity was set by a flag), reads the scene, runs the flow and commits the layer set, the
// optional particles.gpkg and run.json to o.out; throws InputError, NumericalFailure or Cancelled
// with nothing written.
void mudflow_job(MudflowOptions& o, ParameterTable& table, bool adaptive_given, const JobOutput& output);

}  // namespace talus::cli
