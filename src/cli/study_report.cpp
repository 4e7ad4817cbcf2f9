#include "study_report.hpp"

#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include "job_output.hpp"

namespace talus::cli {
namespace {

// A JSON value as text, "" for none.
std::string text_of(const nlohmann::ordered_json& value) {
  if (value.is_null()) return "";
  if (value.is_string()) return value.get<std::string>();
  if (value.is_number()) return printf_text("%g", value.get<double>());
  return value.dump();
}

// The parameters a reader of the report looks for first, per process.
std::string key_parameters(const nlohmann::ordered_json& s) {
  const auto& p = s["parameters"];
  if (s["process"] == "rockfall") {
    return text_of(p["run"]["mode"]) + " mode, " + text_of(p["rock"]["shape"]) + " " + text_of(p["rock"]["size"]) +
           " m, " + text_of(p["rock"]["density"]) + " kg/m3, runs " + text_of(p["run"]["runs"]);
  }
  return text_of(p["mud"]["material"]) + ", " + text_of(p["rheology"]["rheology"]) + ", particles " +
         text_of(p["mud"]["particle_size"]) + " m";
}

std::string key_results(const nlohmann::ordered_json& s) {
  const auto& c = s["counts"];
  if (s["process"] == "rockfall") {
    return text_of(c["sources"]) + " sources, " + text_of(c["trajectories"]) + " trajectories";
  }
  const auto& v = s["volumes_m3"];
  return v.is_object() ? printf_text("released %.0f m3, deposited %.0f m3", v["released"].get<double>(),
                                     v["deposited"].get<double>())
                       : "";
}

}  // namespace

void write_study_report(const nlohmann::ordered_json& record, const std::filesystem::path& out) {
  std::ostringstream md;
  const std::filesystem::path study(text_of(record["study"]));
  md << "# Hazard study: " << study.filename().string() << "\n\n"
     << "Talus " << text_of(record["talus_version"]) << ", study file `" << study.string() << "`, "
     << record["scenarios"].size() << " scenarios in " << printf_text("%.0f", record["seconds"].get<double>())
     << " s. Every figure below comes from `study.json` beside this page; each scenario's folder holds its layers and "
        "its `run.json` with every input (with checksums) and parameter.\n\n";
  const auto& hazard = record["hazard"];
  md << "## Hazard map\n\n";
  if (hazard.contains("maps")) {
    if (std::filesystem::exists(out / "quicklook" / "hazard.png")) md << "![Hazard map](quicklook/hazard.png)\n\n";
    md << "Hazard degrees by the matrix of " << text_of(hazard["guideline"]) << ". Rock-fall return periods "
       << (hazard["rockfall_probability"] == "reach" ? "divided by each cell's reach probability"
                                                     : "applied wherever a rock reaches")
       << "; each cell shows the highest degree of all the scenarios. Source: " << text_of(hazard["source"]) << "\n\n"
       << "| degree | area (km2) | cells |\n|---|---|---|\n";
    for (const auto& d : hazard["maps"]["hazard"]) {
      md << "| " << text_of(d["name"]) << " | " << printf_text("%.3f", d["area_km2"].get<double>()) << " | "
         << text_of(d["cells"]) << " |\n";
    }
    md << "\nFiles: `hazard/hazard.tif`, `hazard/hazard_zones.gpkg` (polygons), per process `hazard/hazard_rockfall.tif`, "
          "`hazard/hazard_mudflow.tif`; `project.qgz` opens them all in QGIS.\n\n";
  } else {
    md << text_of(hazard["note"]) << ".\n\n";
  }
  md << "## Scenarios\n\n| scenario | process | return period (years) | parameters | result | problems |\n"
        "|---|---|---|---|---|---|\n";
  for (const auto& s : record["scenarios"]) {
    md << "| " << text_of(s["name"]) << " | " << text_of(s["process"]) << " | "
       << printf_text("%g", s["return_period_years"].get<double>()) << " | " << key_parameters(s) << " | "
       << key_results(s) << " | " << s["problems"].size() << " |\n";
  }
  if (record.contains("sources")) {
    md << "\n## Rock-fall sources from the slope\n\n| scenario | threshold (degrees) | cells | area (km2) |\n"
          "|---|---|---|---|\n";
    for (const auto& [name, entry] : record["sources"].items()) {
      md << "| " << name << " | " << printf_text("%.1f", entry["threshold_deg"].get<double>()) << " ("
         << text_of(entry["threshold"]) << ") | " << text_of(entry["cells"]) << " | "
         << printf_text("%.4f", entry["area_km2"].get<double>()) << " |\n";
    }
  }
  md << "\n## Problems\n\n";
  bool any = false;
  for (const auto& s : record["scenarios"]) {
    for (const auto& problem : s["problems"]) {
      md << "- " << text_of(s["name"]) << ": " << text_of(problem) << "\n";
      any = true;
    }
  }
  if (!any) md << "None.\n";
  const std::filesystem::path partial = out / ".report.md.partial";
  {
    std::ofstream file(partial, std::ios::binary);
    file << md.str();
    if (!file) throw std::runtime_error("cannot write " + partial.string());
  }
  std::filesystem::rename(partial, out / "report.md");
}

}  // namespace talus::cli
