#include "study_job.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <fstream>
#include <functional>
#include <utility>

#include <nlohmann/json.hpp>

#include "mudflow_job.hpp"
#include "mudflow_parameters.hpp"
#include "rockfall_job.hpp"
#include "rockfall_parameters.hpp"
#include "run_project.hpp"
#include "study_hazard.hpp"
#include "study_region.hpp"
#include "study_report.hpp"
#include "study_sources.hpp"
#include "study_units.hpp"
#include "talus/core/byte_stream.hpp"
#include "talus/core/errors.hpp"
#include "talus/gis/build_commit.hpp"
#include "talus/gis/folder_manifest.hpp"
#include "talus/gis/replaceable_output.hpp"
#include "talus/gis/scene.hpp"

namespace talus::cli {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

// "2 min 5 s", "1 h 3 min", for the time left.
std::string duration_text(double seconds) {
  const long total = std::lround(std::max(seconds, 0.0));
  if (total < 60) return std::to_string(total) + " s";
  if (total < 3600) return std::to_string(total / 60) + " min " + std::to_string(total % 60) + " s";
  return std::to_string(total / 3600) + " h " + std::to_string(total % 3600 / 60) + " min";
}

// One scenario's share of the study's progress: each scenario counts alike, and the time left is
// the wall time so far scaled to the fraction still to do.
class StudyProgress final : public Progress {
 public:
  StudyProgress(Progress& terminal, std::size_t count) : terminal_(terminal), count_(count), start_(Clock::now()) {}
  void begin(std::size_t index, const std::string& name) {
    index_ = index;
    name_ = name;
  }
  void report(double fraction_done, const std::string& phase) override {
    const double done = (static_cast<double>(index_) + std::clamp(fraction_done, 0.0, 1.0)) / static_cast<double>(count_);
    std::string text = name_ + " (" + std::to_string(index_ + 1) + " of " + std::to_string(count_) + "): " + phase;
    if (done > 0.0 && done < 1.0) text += "; study: about " + duration_text(seconds_since(start_) * (1.0 - done) / done) + " left";
    terminal_.report(done, text);
  }
  bool cancelled() const override { return terminal_.cancelled(); }

 private:
  Progress& terminal_;
  std::size_t count_;
  Clock::time_point start_;
  std::size_t index_ = 0;
  std::string name_;
};

// A scenario's options and parameter table, as `talus rockfall` or `talus mudflow` would have
// them with the study's inputs, the scenario's keys and --threads.
struct RockfallScenarioRun {
  RockfallOptions options;
  ParameterTable table = rockfall_parameter_table(options);
};
struct MudflowScenarioRun {
  MudflowOptions options;
  ParameterTable table = mudflow_parameter_table(options);
};

template <typename Run>
void set_up(Run& run, const Study& study, const StudyScenario& s, const StudyChoices& choices) {
  run.options.inputs = study.inputs;
  run.options.inputs.release = s.detect_sources ? detected_sources_path(choices.out, s) : s.release;
  run.options.out = choices.out / "scenarios" / s.name;
  run.options.scenario = s.scenario;
  run.options.command_line = choices.command_line;
  run.table.apply(s.parameters, ParameterTable::Origin::scenario, s.where);
  if (choices.threads) {
    run.options.settings.threads = *choices.threads;
    run.table.pin("run", "threads", "--threads");
  }
}

// A scenario's --memory (docs/study.md, "Tiles").
template <typename Run>
void set_memory(Run& run, const StudyChoices& choices) {
  if (!choices.memory) return;
  run.options.tiles.memory = *choices.memory;
  run.table.pin("tiles", "memory", "--memory");
}

// What checking a scenario tells the study: its [outputs] intensity, and the record its layers
// depend on (study_units.hpp).
struct CheckedScenario {
  std::string intensity;
  nlohmann::ordered_json unit;
};

// The files a scenario reads, for its unit record.
template <typename Options>
std::vector<std::filesystem::path> input_files(const Options& o, const StudyScenario& s) {
  std::vector<std::filesystem::path> files = {o.inputs.dem, o.inputs.lithology, o.inputs.vegetation, o.inputs.materials,
                                              o.inputs.erodible, o.scenario};
  if (!s.detect_sources) files.push_back(o.inputs.release);
  if (std::filesystem::path(o.intensity).extension() == ".toml") files.push_back(o.intensity);
  return files;
}

// What a run of `s` resolves and reads before any work: every parameter, the scene and its release
// (unless the study finds its sources).
CheckedScenario check_scenario(const Study& study, const StudyScenario& s, const StudyChoices& choices,
                               FileChecksums& checksums) {
  if (s.process == StudyProcess::rockfall) {
    RockfallScenarioRun run;
    set_up(run, study, s, choices);
    set_memory(run, choices);
    resolve_rockfall_parameters(run.options, run.table);
    run.options.inputs.run_rock = run.options.settings.rock;
    if (!s.detect_sources) {  // detected sources: read by detect_sources()
      // A region run in tiles reads its other maps tile by tile, during the run.
      gis::Scene scene = gis::load_region(run.options.inputs);
      if (!plan_tiles(scene.dem.elevation.spec(), run.options.tiles, 0).tiled()) gis::add_ground_maps(scene);
    }
    return {run.options.intensity, unit_record(s, nlohmann::ordered_json::parse(run.table.values().dump()),
                                               input_files(run.options, s), checksums)};
  }
  MudflowScenarioRun run;
  set_up(run, study, s, choices);
  set_memory(run, choices);
  run.options.inputs.erodible = s.erodible;
  resolve_mudflow_parameters(run.options, run.table, false);
  run.options.inputs.release_needs_depth = true;
  gis::Scene scene = gis::load_region(run.options.inputs);
  if (!plan_tiles(scene.dem.elevation.spec(), run.options.tiles, 0).tiled()) gis::add_ground_maps(scene);
  return {run.options.intensity,
          unit_record(s, nlohmann::ordered_json::parse(run.table.values().dump()), input_files(run.options, s),
                      checksums)};
}

// A rock fall's sources are shared among the ranks (rockfall_job.hpp), its units of work
// committed under OUT/.units/NAME.parts until its set is (study_units.hpp); a mud flow runs on
// one rank.
void run_scenario(const Study& study, const StudyScenario& s, const StudyChoices& choices, const JobOutput& output,
                  const ProcessRanks& ranks, const nlohmann::ordered_json& unit) {
  if (s.process == StudyProcess::rockfall) {
    RockfallScenarioRun run;
    set_up(run, study, s, choices);
    set_memory(run, choices);
    run.options.unit_parts = unit_parts_folder(choices.out, s);
    run.options.unit_key = unit.dump();
    rockfall_job(run.options, run.table, output, ranks);
    return;
  }
  MudflowScenarioRun run;
  set_up(run, study, s, choices);
  set_memory(run, choices);
  run.options.inputs.erodible = s.erodible;
  mudflow_job(run.options, run.table, false, output);
}

// Under MPI, the mud flows go to the ranks in turn (the k-th to rank k mod N) and run side by
// side, each on one rank, while the rock falls are shared source by source. A mud flow that
// failed on its rank is thrown on every rank at the next meeting: the next rock fall, or the end
// of the scenarios. In one process it is thrown at once, as it happens.
class MudflowTurns {
 public:
  explicit MudflowTurns(const ProcessRanks& ranks) : ranks_(ranks) {}
  int next_rank() { return static_cast<int>(count_++ % static_cast<std::size_t>(ranks_.size())); }
  void run_own(const std::function<void()>& step) {
    if (ranks_.size() == 1) return step();
    if (failed_) return;  // this rank only waits for the meeting now
    try {
      step();
    } catch (...) {
      failed_ = std::current_exception();
    }
  }
  void meet() {
    together(ranks_, [&] {
      if (failed_) std::rethrow_exception(std::exchange(failed_, nullptr));
    });
  }

 private:
  const ProcessRanks& ranks_;
  std::size_t count_ = 0;
  std::exception_ptr failed_;
};

// Which scenarios an earlier run finished, as rank 0 reads them, on every rank.
std::vector<std::uint8_t> scenarios_done(const Study& study, const StudyChoices& choices,
                                         const std::vector<nlohmann::ordered_json>& units, const ProcessRanks& ranks) {
  std::vector<std::uint8_t> done(study.scenarios.size(), 0);
  if (ranks.root()) {
    for (std::size_t k = 0; k < done.size(); ++k) done[k] = unit_done(choices.out, study.scenarios[k], units[k]) ? 1 : 0;
  }
  return ranks.broadcast(done);
}

// Each scenario's wall time on the rank that ran it (the longest over the ranks), on rank 0.
std::vector<double> scenario_seconds(const std::vector<double>& mine, const ProcessRanks& ranks) {
  ByteWriter out;
  out.put_vector(mine);
  std::vector<double> longest = mine;
  for (const auto& bytes : ranks.gather(out.bytes())) {
    ByteReader in(bytes);
    std::vector<double> theirs;
    in.get_vector(theirs);
    for (std::size_t k = 0; k < longest.size() && k < theirs.size(); ++k) longest[k] = std::max(longest[k], theirs[k]);
  }
  return longest;
}

nlohmann::json read_json(const std::filesystem::path& path) {
  std::ifstream file(path);
  return nlohmann::json::parse(file);
}

// study.json: the study file, and per scenario its process, return period, folder and what its
// run.json says of parameters, counts, problems and timings.
nlohmann::ordered_json study_record(const Study& study, const StudyChoices& choices, const std::vector<double>& seconds,
                                    const StudyZoning& zoning, const nlohmann::ordered_json& hazard,
                                    const nlohmann::ordered_json& region, const nlohmann::ordered_json& sources) {
  nlohmann::ordered_json record;
  record["talus_version"] = TALUS_VERSION;
  record["git_commit"] = gis::git_commit();
  record["command_line"] = choices.command_line;
  record["study"] = std::filesystem::absolute(study.file).string();
  nlohmann::ordered_json scenarios = nlohmann::ordered_json::array();
  double total = 0;
  for (std::size_t k = 0; k < study.scenarios.size(); ++k) {
    const StudyScenario& s = study.scenarios[k];
    const std::filesystem::path folder = std::filesystem::path("scenarios") / s.name;
    const nlohmann::json run = read_json(choices.out / folder / "run.json");
    scenarios.push_back({{"name", s.name},
                         {"process", to_string(s.process)},
                         {"return_period_years", s.return_period_years},
                         {"annual_frequency", 1.0 / s.return_period_years},
                         {"folder", folder.string()},
                         {"seconds", seconds[k]},
                         {"parameters", run["parameters"]},
                         {"counts", run["counts"]},
                         {"problems", run["problems"]},
                         {"volumes_m3", run.value("volumes_m3", nlohmann::json())},
                         {"tiles", run.value("tiles", nlohmann::json())},
                         {"timings_s", run["timings_s"]}});
    total += seconds[k];
  }
  record["scenarios"] = scenarios;
  if (!sources.empty()) record["sources"] = sources;
  record["hazard"] = zoning.matrix ? hazard : nlohmann::ordered_json({{"note", zoning.note}});
  record["region"] = region;
  record["seconds"] = total;
  return record;
}

// OUT may be new, empty, or a study's earlier output (with a staging folder a killed run left).
// A complete study's manifest (.talus-files.json) tells its files from the user's, which stay;
// without one, any name a study does not write is not ours to write beside. Files of the study
// changed since it wrote them, or a folder that cannot be written, are refused before any work.
void check_study_folder(const std::filesystem::path& out) {
  std::error_code ec;
  if (!std::filesystem::exists(out, ec)) return;
  const std::string shown = out.string() + " (--out)";
  if (!std::filesystem::is_directory(out, ec)) throw InputError(shown + ": is a file, not a folder");
  gis::check_replaceable_folder(out, shown);
  gis::FolderSurvey survey;
  try {
    survey = gis::survey_folder(out);
  } catch (const std::exception& e) {
    throw InputError(shown + ": cannot read what it holds: " + e.what());
  }
  if (!survey.changed.empty()) throw InputError(shown + ": " + gis::changed_since_written(survey.changed));
  if (survey.recorded) return;
  std::vector<std::filesystem::path> foreign;
  for (const auto& entry : std::filesystem::directory_iterator(out, ec)) {
    const std::string name = entry.path().filename().string();
    // What a study writes, and the hidden files and staging folders it writes them through.
    const bool ours = name == "scenarios" || name == "hazard" || name == "region" || name == "sources" || name == "study.json" ||
                      name == "report.md" || name == "project.qgz" || name == "hillshade.tif" ||
                      name == "quicklook" || name.front() == '.';
    if (!ours) foreign.push_back(name);
  }
  if (!foreign.empty()) {
    std::sort(foreign.begin(), foreign.end());
    throw InputError(shown + ": holds files that are not a Talus study (" + gis::list_of_names(foreign) +
                     "); give a new or empty folder");
  }
}

// What the study checked before any scenario runs: each scenario's unit record, the zoning, and the record of the sources it found (written by rank 0).
struct CheckedStudy {
  std::vector<nlohmann::ordered_json> units;
  std::optional<StudyZoning> zoning;
  nlohmann::ordered_json sources;
};

CheckedStudy check_study(const Study& study, const StudyChoices& choices, const JobOutput& output,
                         const ProcessRanks& ranks) {
  check_study_folder(choices.out);
  // The manifest describes a complete study: until this one is, the folder has none.
  if (ranks.root()) std::filesystem::remove(choices.out / gis::kFolderManifestName);
  CheckedStudy checked;
  std::vector<std::string> intensity;
  std::vector<std::optional<DetectedSources>> detected;
  std::optional<SlopeAnalysis> slopes;  // read once, for the first scenario that finds its sources
  FileChecksums checksums;
  for (const StudyScenario& s : study.scenarios) {
    CheckedScenario scenario = check_scenario(study, s, choices, checksums);
    intensity.push_back(scenario.intensity);
    checked.units.push_back(std::move(scenario.unit));
    if (s.detect_sources && !slopes) slopes = analyse_slopes(study);
    detected.push_back(s.detect_sources ? std::optional(detect_sources(*slopes, s)) : std::nullopt);
    if (detected.back()) {
      output.say(printf_text("Sources of %s from the slope: %zu cells steeper than %.1f degrees (%s)", s.name.c_str(),
                             detected.back()->cells, detected.back()->threshold_deg,
                             detected.back()->threshold_from_dem ? "the DEM's cliff threshold, Loye et al. 2009"
                                                                 : "source_slope"));
    }
  }
  checked.zoning = study_zoning(study, intensity);
  // Rank 0 writes the sources; every rank reads them in its scenarios' runs.
  const bool any_detected = std::any_of(detected.begin(), detected.end(), [](const auto& d) { return d.has_value(); });
  if (any_detected && ranks.root()) {
    checked.sources = write_detected_sources(study, choices.out, choices.command_line, detected);
  }
  return checked;
}

}  // namespace

void study_job(const Study& study, const StudyChoices& choices, const JobOutput& output, const ProcessRanks& ranks) {
  const std::string count =
      std::to_string(study.scenarios.size()) + (study.scenarios.size() == 1 ? " scenario" : " scenarios");
  output.say("Checking " + count + " of " + study.file.string() + " ...");
  CheckedStudy checked;
  together(ranks, [&] { checked = check_study(study, choices, output, ranks); });
  const std::vector<nlohmann::ordered_json>& units = checked.units;
  const StudyZoning& zoning = *checked.zoning;
  const nlohmann::ordered_json& sources = checked.sources;
  StudyProgress progress(output.progress, study.scenarios.size());
  const std::vector<std::uint8_t> done = scenarios_done(study, choices, units, ranks);
  MudflowTurns mudflows(ranks);
  std::vector<double> seconds(study.scenarios.size(), 0.0);
  for (std::size_t k = 0; k < study.scenarios.size(); ++k) {
    const StudyScenario& s = study.scenarios[k];
    progress.begin(k, s.name);
    output.say("Scenario " + std::to_string(k + 1) + " of " + std::to_string(study.scenarios.size()) + ": " + s.name +
               " (" + to_string(s.process) + ", return period " + printf_text("%g", s.return_period_years) + " years)");
    const auto start = Clock::now();
    const JobOutput indented{[&](const std::string& line) { output.say("  " + line); }, progress};
    if (done[k] != 0) {
      output.say("  already done: its layers were computed from the same parameters and inputs (resumed)");
    } else if (s.process == StudyProcess::rockfall) {
      mudflows.meet();
      run_scenario(study, s, choices, indented, ranks, units[k]);
      if (ranks.root()) mark_unit_done(choices.out, s, units[k]);
    } else if (const int owner = mudflows.next_rank(); owner == ranks.rank()) {
      mudflows.run_own([&] {
        run_scenario(study, s, choices, indented, ranks, units[k]);
        mark_unit_done(choices.out, s, units[k]);
      });
    } else {
      output.say("  runs on MPI rank " + std::to_string(owner) + ", beside this one; its lines are in its run.json");
    }
    seconds[k] = seconds_since(start);
  }
  mudflows.meet();
  seconds = scenario_seconds(seconds, ranks);
  if (!ranks.root()) return;  // rank 0 writes the study's own files
  nlohmann::ordered_json hazard;
  if (zoning.matrix) {
    hazard = write_study_hazard(study, choices, zoning, output);
  } else {
    output.say("note: " + zoning.note);
  }
  const nlohmann::ordered_json region = write_region_layers(study, choices, output);
  const nlohmann::ordered_json record = study_record(study, choices, seconds, zoning, hazard, region, sources);
  const std::filesystem::path partial = choices.out / ".study.json.partial";
  {
    std::ofstream file(partial);
    file << record.dump(2) << '\n';
    if (!file) throw std::runtime_error("cannot write " + partial.string());
  }
  std::filesystem::rename(partial, choices.out / "study.json");
  const std::string project_line =
      write_project_if_wanted(choices.project, choices.out, choices.out, "study", study.inputs.dem, "");
  write_study_report(record, choices.out);
  gis::write_folder_manifest(choices.out);
  if (!project_line.empty()) output.say(project_line);
  output.say("Study written to " + choices.out.string() + ": " + count + " under scenarios/, " +
             (zoning.matrix ? "the hazard map under hazard/, " : "") + "the region layers under region/, study.json, report.md");
}

}  // namespace talus::cli
