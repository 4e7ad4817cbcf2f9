// The study's one-page report (issue 19, item 7; docs/study.md, "Summary"): DIR/report.md, a
// Markdown page a consultant can attach, from study.json: the hazard map's quicklook and areas,
// the table of scenarios with their parameters and results, the sources found, every problem.
#pragma once

#include <filesystem>

#include <nlohmann/json.hpp>

namespace talus::cli {

// Writes OUT/report.md (under a temporary name, renamed when complete).
void write_study_report(const nlohmann::ordered_json& record, const std::filesystem::path& out);

}  // namespace talus::cli
