// `talus calibrate` (issue 4): fits the fast mode's restitution coefficients of each lithology
// class to the full model on simple slopes (paper 3.3, "Fast Bounce mode", last paragraph) and
// writes the materials table with them (TOML) and a report beside it (JSON). docs/calibration.md.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>
#include <set>
#include <sstream>
#include <system_error>
#include <unistd.h>

#include "commands.hpp"
#include "number_list.hpp"
#include "parameter_table.hpp"
#include "terminal_progress.hpp"
#include "whole_number.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/materials_file.hpp"
#include "talus/gis/replaceable_output.hpp"
#include "talus/gis/run_record.hpp"
#include "talus/rockfall/calibration.hpp"

namespace talus::cli {
namespace {

namespace fs = std::filesystem;

struct CalibrateOptions {
  fs::path out;
  fs::path materials;
  std::string classes;
  std::string slopes = "30,40";
  double block_size = 1.0;      // m, sphere diameter
  double density = 2700.0;      // kg/m3
  std::uint64_t runs = 2;
  std::uint64_t fast_runs = 8;
  std::uint64_t seed = 1;
  int threads = 0;
  std::vector<std::string> command_line;
};

// A number as the user would write it (1.5, not 1.500000).
std::string number(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

// --classes: lithology codes of the table, each once; empty text means every class.
std::vector<int> parse_classes(const std::string& text, const MaterialsTable& table, const std::string& table_name) {
  std::vector<int> codes;
  if (text.empty()) return codes;
  std::set<int> seen;
  for (double value : parse_number_list("--classes", text)) {
    if (value != std::floor(value) || std::abs(value) > 1e9) {
      throw InputError("--classes " + text + ": class codes are integers");
    }
    const int code = static_cast<int>(value);
    if (table.find_lithology(code) == nullptr) {
      throw InputError("--classes " + text + ": no lithology class " + std::to_string(code) + " in " + table_name);
    }
    if (!seen.insert(code).second) throw InputError("--classes " + text + ": class " + std::to_string(code) + " given twice");
    codes.push_back(code);
  }
  return codes;
}

// The report's figures of one model on one slope.
nlohmann::ordered_json outcome_json(const SlopeOutcome& outcome) {
  return {{"median_runout_m", outcome.median_runout}, {"median_jump_m", outcome.median_jump}, {"left_share", outcome.left_share}};
}

nlohmann::ordered_json class_json(const ClassCalibration& c, const CalibrationSettings& settings) {
  nlohmann::ordered_json slopes = nlohmann::ordered_json::array();
  for (const SlopeComparison& s : c.slopes) {
    slopes.push_back({{"angle_deg", s.angle},
                      {"full", outcome_json(s.full)},
                      {"fast_before", outcome_json(s.fast_before)},
                      {"fast_after", outcome_json(s.fast_after)},
                      {"runout_error_before", runout_error(s.full, s.fast_before, settings)},
                      {"runout_error_after", runout_error(s.full, s.fast_after, settings)}});
  }
  return {{"code", c.code},
          {"name", c.name},
          {"restitution_normal", {{"before", c.restitution_normal_before}, {"after", c.restitution_normal}}},
          {"restitution_tangential", {{"before", c.restitution_tangential_before}, {"after", c.restitution_tangential}}},
          {"fitted", c.fitted},
          {"objective", {{"before", c.objective_before}, {"after", c.objective_after}}},
          {"evaluations", c.evaluations},
          {"slopes", slopes},
          {"timings_s", {{"reference", c.reference_seconds}, {"fit", c.fit_seconds}}}};
}

nlohmann::ordered_json settings_json(const CalibrationSettings& s) {
  return {{"rock", {{"shape", "sphere"}, {"diameter_m", s.rock.axes.x()}, {"density_kg_m3", s.rock.density}}},
          {"scene",
           {{"slope_angles_deg", s.scene.slope_angles},
            {"slope_length_m", s.scene.slope_length},
            {"runout_length_m", s.scene.runout_length},
            {"crest_length_m", s.scene.crest_length},
            {"side_margin_m", s.scene.side_margin},
            {"cell_size_m", s.scene.cell_size},
            {"sources", s.scene.sources},
            {"source_spacing_m", s.scene.source_spacing}}},
          {"runs_per_source", s.runs_per_source},
          {"fast_runs_per_source", s.fast_runs_per_source},
          {"seed", s.seed},
          {"objective", {{"jump_weight", s.jump_weight}}},
          {"search",
           {{"restitution_min", s.restitution_min},
            {"restitution_max", s.restitution_max},
            {"grid_points", s.grid_points},
            {"refine_step", s.refine_step}}}};
}

// One summary line per class: coefficients before -> after, then per slope the full model's
// median runout and the fast mode's before -> after, with the error after for a fitted class
// (against at least one rock diameter); then a note for each class left as it was and for each
// slope where most full-model runs left the scene (its median is then a lower bound).
void print_summary(const CalibrationResult& result, const CalibrationSettings& settings) {
  std::printf("%-5s %-24s %-13s %-13s %s\n", "class", "name", "Rn (-)", "Rt (-)",
              "per slope: full-model median runout (m); fast mode before -> after (m), error after");
  for (const ClassCalibration& c : result.classes) {
    std::printf("%-5d %-24.24s %.3f->%.3f   %.3f->%.3f  ", c.code, c.name.c_str(), c.restitution_normal_before,
                c.restitution_normal, c.restitution_tangential_before, c.restitution_tangential);
    for (const SlopeComparison& s : c.slopes) {
      std::printf(" | %2.0f deg: %.1f; %.1f -> %.1f", s.angle, s.full.median_runout, s.fast_before.median_runout,
                  s.fast_after.median_runout);
      if (c.fitted) std::printf(" (%+.1f %%)", 100.0 * runout_error(s.full, s.fast_after, settings));
    }
    if (!c.fitted) std::printf(" | not fitted");
    std::printf("\n");
  }
  for (const ClassCalibration& c : result.classes) {
    if (!c.fitted) {
      std::printf("note: class %d: the full model's rocks hardly move on these slopes (median runout under %.0f m), "
                  "so its coefficients are kept; steeper --slopes may calibrate it\n", c.code, settings.min_runout);
    }
    for (const SlopeComparison& s : c.slopes) {
      if (s.full.left_share <= 0.5) continue;
      std::printf("note: class %d, %.0f deg: %.0f %% of the full-model runs left the scene, so its median runout is a "
                  "lower bound\n", c.code, s.angle, 100.0 * s.full.left_share);
    }
  }
}

// A hidden temporary name beside `path`, renamed to it only once everything is written.
fs::path temporary_beside(const fs::path& path) {
  return path.parent_path() / ("." + path.filename().string() + ".partial-" + std::to_string(getpid()));
}

// Writes `text` to `path`; std::runtime_error naming the path when that fails.
void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

// Checks every option before any work, so that bad input writes nothing (docs/architecture.md section 3).
void check_options(const CalibrateOptions& o) {
  if (o.out.extension() != ".toml") throw InputError("--out " + o.out.string() + ": give a .toml file name");
  if (fs::is_directory(o.out)) throw InputError("--out " + o.out.string() + ": is a folder");
  const fs::path folder = o.out.parent_path().empty() ? fs::path(".") : o.out.parent_path();
  if (!fs::is_directory(folder)) throw InputError("--out " + o.out.string() + ": folder " + folder.string() + " does not exist");
  fs::path report = o.out;
  report.replace_extension(".json");
  gis::check_replaceable_file(o.out, "--out " + o.out.string());
  gis::check_replaceable_file(report, "--out " + o.out.string() + " (its report " + report.string() + ")");
  if (!(o.block_size > 0.01 && o.block_size < 100.0)) {
    throw InputError("--block-size " + number(o.block_size) + ": the diameter must lie between 0.01 and 100 m");
  }
  if (!(o.density >= 500.0 && o.density <= 6000.0)) {
    throw InputError("--density " + number(o.density) + ": expected 500-6000 kg/m3");
  }
  if (o.runs == 0) throw InputError("--runs 0: at least one run per release point");
  if (o.fast_runs == 0) throw InputError("--fast-runs 0: at least one run per release point");
  if (o.threads < 0 || o.threads > kMaxThreads) {
    throw InputError("--threads " + std::to_string(o.threads) + ": expected 0 (all cores) or 1-" +
                     std::to_string(static_cast<int>(kMaxThreads)));
  }
}

int run_calibrate_command(const CalibrateOptions& o) {
  const auto start = std::chrono::steady_clock::now();
  check_options(o);
  const MaterialsTable table = o.materials.empty() ? builtin_materials() : gis::read_materials(o.materials);
  const std::string table_name = o.materials.empty() ? "the built-in materials table" : o.materials.string();
  const std::vector<int> codes = parse_classes(o.classes, table, table_name);
  CalibrationSettings settings;
  settings.scene.slope_angles = parse_number_list("--slopes", o.slopes);
  for (double angle : settings.scene.slope_angles) {
    if (!(angle >= 10.0 && angle <= 80.0)) throw InputError("--slopes " + o.slopes + ": angles must lie between 10 and 80 deg");
  }
  settings.rock.shape = BlockShape::sphere;
  settings.rock.axes = Eigen::Vector3d::Constant(o.block_size);
  settings.rock.density = o.density;
  settings.runs_per_source = o.runs;
  settings.fast_runs_per_source = o.fast_runs;
  settings.seed = o.seed;
  settings.threads = o.threads;
  gis::RunRecord record;
  record.set_command_line(o.command_line);
  if (!o.materials.empty()) record.add_input("materials", o.materials, nullptr);

  const std::size_t class_count = codes.empty() ? table.lithology.size() : codes.size();
  std::printf("Calibrating %zu lithology classes on %zu slopes, %d release points x %llu full-model runs each ...\n",
              class_count, settings.scene.slope_angles.size(), settings.scene.sources,
              static_cast<unsigned long long>(o.runs));
  std::fflush(stdout);
  TerminalProgress progress;
  const CalibrationResult result = calibrate_fast_mode(table, codes, settings, &progress);

  record.set_parameters(settings_json(settings));
  nlohmann::ordered_json classes = nlohmann::ordered_json::array();
  for (const ClassCalibration& c : result.classes) classes.push_back(class_json(c, settings));
  record.set("classes", classes);
  record.set("materials_written", fs::absolute(o.out).string());
  record.add_timing("calibrate", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());

  fs::path report = o.out;
  report.replace_extension(".json");
  const fs::path toml_temporary = temporary_beside(o.out), json_temporary = temporary_beside(report);
  try {
    write_text(toml_temporary, gis::materials_to_toml(result.materials));
    record.write(json_temporary);
    fs::rename(toml_temporary, o.out);
    fs::rename(json_temporary, report);
  } catch (...) {
    std::error_code ignored;
    fs::remove(toml_temporary, ignored);
    fs::remove(json_temporary, ignored);
    throw;
  }
  print_summary(result, settings);
  std::printf("Materials written to %s (use: talus rockfall --mode fast --materials %s), report %s\n", o.out.c_str(),
              o.out.c_str(), report.c_str());
  return 0;
}

}  // namespace

void add_calibrate_command(CLI::App& app, Action& action, const std::vector<std::string>& command_line) {
  auto o = std::make_shared<CalibrateOptions>();
  o->command_line = command_line;
  CLI::App* cmd = app.add_subcommand("calibrate", "Fit the fast mode's restitution coefficients to the full model on simple slopes");
  cmd->add_option("--out", o->out, "Materials table to write (.toml); a report .json is written beside it")->required();
  cmd->add_option("--materials", o->materials, "Materials table to start from (TOML); default: built-in");
  cmd->add_option("--classes", o->classes, "Lithology codes to calibrate, e.g. 1,2,4; default: every class");
  cmd->add_option("--block-size", o->block_size, "Sphere diameter (m)")->default_val(1.0);
  cmd->add_option("--density", o->density, "Rock density (kg/m3)")->default_val(2700.0);
  cmd->add_option("--slopes", o->slopes, "Slope angles of the calibration scenes (deg)")->default_val("30,40");
  cmd->add_option("--runs", o->runs, "Full-model runs per release point and slope (12 release points)")->default_val(2);
  cmd->add_option("--fast-runs", o->fast_runs, "Fast-mode runs per release point and slope")->default_val(8);
  cmd->add_option("--seed", o->seed, "Random seed")->default_val(1)->check(whole_number());
  cmd->add_option("--threads", o->threads, "Threads (default: all cores)");
  cmd->callback([o, &action] { action = [o] { return run_calibrate_command(*o); }; });
}

}  // namespace talus::cli
