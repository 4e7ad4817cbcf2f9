// The QGIS project and quicklooks of a run (issue 17, item 8; docs/layers.md, "QGIS project and
// quicklooks"): gis/qgis/run_project.py, built into the program, run on Debian's Python with
// QGIS once the layer set is committed.
#pragma once

#include <filesystem>
#include <string>

namespace talus::cli {

struct RunProjectOutcome {
  bool written = false;
  bool qgis_missing = false;  // nothing to run it with, rather than a failure
  std::string message;  // what was written, or why nothing was (for a note or problem line)
};

// Writes STAGING/project.qgz, STAGING/hillshade.tif and STAGING/quicklook/*.png for `process`
// ("rockfall", "mudflow") over `dem`, with the `release` layer, into the staging folder of a set
// that will be committed as `out` (the message names `out`; the project's relative paths hold
// after the swap, the staging folder lying beside `out`). Python is $TALUS_PYTHON or /usr/bin/python3;
// without it, or without its QGIS, nothing is written and the outcome says so. A script that
// fails or runs past `timeout_s` leaves no partial project (it renames when complete).
RunProjectOutcome write_run_project(const std::filesystem::path& staging, const std::filesystem::path& out,
                                    const std::string& process,
                                    const std::filesystem::path& dem, const std::filesystem::path& release,
                                    double timeout_s);

// --project on|off ([outputs] project); throws InputError for anything else.
bool project_wanted(const std::string& setting);

// Before the layer set is committed: writes the project into its staging folder when wanted
// (timeout 600 s) and returns the line to print once the set is committed: where the project
// is, or a `note:` (no QGIS here) or `problem:` (the script failed) saying why there is none;
// empty when not wanted. The layers stand either way.
std::string write_project_if_wanted(bool wanted, const std::filesystem::path& staging, const std::filesystem::path& out,
                                    const std::string& process, const std::filesystem::path& dem,
                                    const std::filesystem::path& release);

}  // namespace talus::cli
