// The problem a mud-flow run reports when the flow was still moving at the simulated time limit
// (issue 18, item 4): its layers miss the rest of the flow, so the run says so instead of
// passing for a finished one.
#pragma once

#include <string>
#include <vector>

#include "talus/mudflow/mudflow_simulation.hpp"

namespace talus::cli {

// One problem line ("mud flow: ...") when the run ended at [run] duration with particles still
// flowing, naming the kinetic energy left against its peak and the end criterion; none otherwise.
std::vector<std::string> unfinished_flow_problems(const MudflowResult& result, const MudflowSettings& settings);

}  // namespace talus::cli
