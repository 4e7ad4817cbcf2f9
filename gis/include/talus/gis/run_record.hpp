// run.json (docs/architecture.md section 3): what a run did, for whoever finds its layers later: software
// version, command line, inputs (path, size, CRS, SHA-256 checksum), every resolved parameter,
// seed, threads, counts and wall-clock time per phase. Rock fall and mud flow fill it alike.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "talus/core/grid_spec.hpp"

namespace talus::gis {

class RunRecord {
 public:
  // Starts the record at the current date and time (UTC).
  RunRecord();

  void set_command_line(const std::vector<std::string>& arguments);
  // Records an input file under its role ("dem", "release", ...): absolute path, bytes and
  // SHA-256 of the named file (of a multi-file format such as .shp, that file only); columns,
  // rows and CRS from `grid` when given (the grid the run used), else as GDAL reads the file: a
  // raster's columns, rows and CRS, a vector's first layer, feature count and CRS, nothing more
  // for other files. Throws std::runtime_error naming a file it cannot read, std::logic_error
  // for a role recorded twice.
  void add_input(const std::string& role, const std::filesystem::path& path, const GridSpec* grid);
  // The resolved parameters, e.g. {section: {name: value}}.
  void set_parameters(nlohmann::ordered_json parameters);
  // Any other item (seed, threads, counts, notes), replacing one of the same key; the keys the
  // record fills itself are a std::logic_error.
  void set(const std::string& key, nlohmann::ordered_json value);
  // Adds wall-clock seconds to a phase ("read_inputs", "simulate", ...).
  void add_timing(const std::string& phase, double seconds);

  // The record as run.json holds it: Talus and GDAL versions, start and finishing (now) times,
  // the host's hardware threads, then what was recorded, timings last.
  nlohmann::ordered_json to_json() const;
  // Writes to_json() as indented UTF-8 JSON; throws std::runtime_error naming the path.
  void write(const std::filesystem::path& path) const;

 private:
  std::string started_utc_;
  std::vector<std::string> command_line_;
  nlohmann::ordered_json inputs_ = nlohmann::ordered_json::object();
  nlohmann::ordered_json parameters_ = nlohmann::ordered_json::object();
  nlohmann::ordered_json items_ = nlohmann::ordered_json::object();
  nlohmann::ordered_json timings_ = nlohmann::ordered_json::object();
};

// SHA-256 of a file's bytes as 64 lowercase hex digits; throws std::runtime_error naming it.
std::string sha256_of_file(const std::filesystem::path& path);

}  // namespace talus::gis
