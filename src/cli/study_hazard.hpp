// The hazard map of a study (issue 19, item 3; docs/study.md, "Hazard map"): every scenario's
// intensity.tif with its return period through the guideline's hazard matrix, the highest degree
// per cell, as DIR/hazard/: hazard.tif (both processes), hazard_rockfall.tif and
// hazard_mudflow.tif (each process that has scenarios), hazard_zones.gpkg, styles and run.json.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "job_output.hpp"
#include "study_file.hpp"
#include "study_job.hpp"
#include "talus/hazard/hazard_matrix.hpp"

namespace talus::cli {

// How the study's scenarios are zoned: the guideline all of them classify intensity by, and its
// matrix; none when every scenario writes no intensity layer or the guideline has no matrix (the
// note says why).
struct StudyZoning {
  std::optional<HazardMatrix> matrix;
  std::string guideline;  // the scenarios' [outputs] intensity
  std::string note;       // why there is no hazard map; empty when there is one
};

// Checked before any scenario runs: `intensity` holds each scenario's resolved [outputs]
// intensity, in the study's order. Scenarios that differ (one "none", or two guidelines) or an
// intensity class the matrix has no row for are InputError naming the scenario.
StudyZoning study_zoning(const Study& study, const std::vector<std::string>& intensity);

// Writes DIR/hazard/ from the finished scenarios' intensity layers and returns study.json's
// "hazard" entry: the guideline, the matrix's source and per map and degree its cells and area.
nlohmann::ordered_json write_study_hazard(const Study& study, const StudyChoices& choices, const StudyZoning& zoning,
                                          const JobOutput& output);

}  // namespace talus::cli
