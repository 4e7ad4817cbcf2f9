// The region's merged layers (issue 19, item 2; docs/study.md, "Region layers"): per process,
// the envelope of its scenarios, cell by cell: the largest value over the scenarios of each
// hazard layer (reach probability, energies, jump height, velocity, flow depth, pressure,
// deposit, intensity class) and the earliest arrival of a mud flow, as DIR/region/rockfall/ and
// DIR/region/mudflow/, styled as the scenarios' layers.
#pragma once

#include <nlohmann/json.hpp>

#include "job_output.hpp"
#include "study_file.hpp"
#include "study_job.hpp"

namespace talus::cli {

// Writes DIR/region/PROCESS/ for each process with scenarios, from their finished layers, and
// returns study.json's "region" entry: per process its folder, layers and scenarios.
nlohmann::ordered_json write_region_layers(const Study& study, const StudyChoices& choices, const JobOutput& output);

}  // namespace talus::cli
