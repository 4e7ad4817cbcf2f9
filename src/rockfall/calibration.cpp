// Calibration of the fast bounce mode against the full model on simple slopes (paper 3.3,
// "Fast Bounce mode", last paragraph). Scenes, objective and search: docs/calibration.md.
#include "talus/rockfall/calibration.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <map>
#include <numbers>
#include <tuple>
#include <utility>

#include "talus/core/errors.hpp"

namespace talus {
namespace {

// Elevation of the flat runout zone of a calibration scene (m); any value would do.
constexpr double kFootElevation = 100.0;

double radians(double degrees) { return degrees * std::numbers::pi / 180.0; }

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Median of a sample of runouts or jumps (m; mean of the two middle values for an even count,
// 0 when empty), as run.json's runout summary takes it.
double median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n % 2 == 1 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

// Reports a part [begin, end] (fractions of the whole) of a longer task to the caller's
// progress, with a phase prefix; cancellation passes through.
class PartProgress final : public Progress {
 public:
  PartProgress(Progress* outer, double begin, double end, std::string prefix)
      : outer_(outer), begin_(begin), end_(end), prefix_(std::move(prefix)) {}
  void report(double fraction_done, const std::string& phase) override {
    if (outer_ != nullptr) outer_->report(begin_ + std::clamp(fraction_done, 0.0, 1.0) * (end_ - begin_), prefix_ + phase);
  }
  bool cancelled() const override { return outer_ != nullptr && outer_->cancelled(); }

 private:
  Progress* outer_;
  double begin_, end_;
  std::string prefix_;
};

// Paper 3.4 ("height over the ground" of the statistical maps): the largest height of a run's
// centre above the unperturbed ground (m), over its samples after the release sample.
double largest_jump(const GroundModel& ground, const TrajectoryLine& line) {
  double largest = 0.0;
  for (std::size_t i = 1; i < line.vertices.size(); ++i) {
    const Eigen::Vector3d& p = line.vertices[i].position;
    if (ground.contains(p.x(), p.y())) largest = std::max(largest, p.z() - ground.elevation(p.x(), p.y()));
  }
  return largest;
}

// Paper 2.1: the class's node material, with the given fast-mode coefficients (-) and the
// vegetation's deperdition (1/m).
GroundMaterial class_material(const LithologyClass& lithology, double vegetation_deperdition, double restitution_normal,
                              double restitution_tangential) {
  LithologyClass varied = lithology;
  varied.restitution_normal = restitution_normal;
  varied.restitution_tangential = restitution_tangential;
  return GroundMaterial::from(varied, vegetation_deperdition);
}

// The fast mode's medians on every calibration slope for one pair of coefficients; the same
// seed for every pair (common random numbers), so that the objective is a deterministic
// function of the coefficients.
class FastEvaluator {
 public:
  FastEvaluator(const LithologyClass& lithology, double vegetation_deperdition, const std::vector<ReleaseSource>& sources,
                const CalibrationSettings& settings)
      : lithology_(lithology), deperdition_(vegetation_deperdition), sources_(sources), settings_(settings),
        model_(settings.fast) {}

  std::vector<SlopeOutcome> outcomes(double restitution_normal, double restitution_tangential) const {
    const GroundMaterial material = class_material(lithology_, deperdition_, restitution_normal, restitution_tangential);
    std::vector<SlopeOutcome> result;
    for (double angle : settings_.scene.slope_angles) {
      const GroundModel ground = calibration_ground(settings_.scene, angle, material);
      result.push_back(simulate_slope(ground, sources_, model_, settings_, settings_.fast_runs_per_source, nullptr));
    }
    return result;
  }

 private:
  const LithologyClass& lithology_;
  double deperdition_;
  const std::vector<ReleaseSource>& sources_;
  const CalibrationSettings& settings_;
  FastBounce model_;
};

// Minimises the objective over the search box (docs/calibration.md, "Search"): a coarse grid
// and the table's point, then a pattern search from each of the best few of them, halving the
// step until it is below refine_step; the best point found wins. Every value is cached by its
// exact coefficients, so revisited points cost nothing.
class CoefficientSearch {
 public:
  // The eight neighbours of a point, in steps of (Rn, Rt).
  static constexpr std::pair<int, int> kDirections[] = {{1, 0}, {-1, 0}, {0, 1}, {0, -1}, {1, 1}, {-1, -1}, {1, -1}, {-1, 1}};

  CoefficientSearch(const FastEvaluator& evaluator, const std::vector<SlopeOutcome>& target,
                    const CalibrationSettings& settings, PartProgress& progress)
      : evaluator_(evaluator), target_(target), settings_(settings), progress_(progress) {}

  // `table`: the table's coefficients, a candidate too, so that the fit is never worse on the
  // slopes than the table it starts from.
  std::pair<double, double> minimise(const std::pair<double, double>& table) {
    const double lo = settings_.restitution_min, hi = settings_.restitution_max;
    const int n = std::max(settings_.grid_points, 2);
    const double grid_step = (hi - lo) / (n - 1);
    std::vector<std::pair<double, std::pair<double, double>>> grid;  // (value, point)
    const std::pair<double, double> start{std::clamp(table.first, lo, hi), std::clamp(table.second, lo, hi)};
    grid.push_back({value(start), start});
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) {
        const std::pair<double, double> point{lo + i * grid_step, lo + j * grid_step};
        grid.push_back({value(point), point});
      }
    }
    std::stable_sort(grid.begin(), grid.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    const std::size_t starts = std::min<std::size_t>(static_cast<std::size_t>(std::max(settings_.refine_starts, 1)), grid.size());
    std::pair<double, double> best = grid.front().second;
    double best_value = grid.front().first;
    for (std::size_t k = 0; k < starts; ++k) {
      const auto [point, v] = refine(grid[k].second, grid[k].first, 0.5 * grid_step);
      if (v < best_value) {
        best_value = v;
        best = point;
      }
    }
    return best;
  }
  int evaluations() const { return static_cast<int>(cache_.size()); }

 private:
  // Pattern search from `best`: tries a step along each coefficient and along both diagonals
  // (the objective's valleys run diagonally: more Rn and less Rt give similar runouts), moves to
  // the best improvement, and halves the step when none improves.
  std::pair<std::pair<double, double>, double> refine(std::pair<double, double> best, double best_value, double step) {
    const double lo = settings_.restitution_min, hi = settings_.restitution_max;
    while (step >= settings_.refine_step) {
      const std::pair<double, double> centre = best;
      bool moved = false;
      for (const auto& [di, dj] : kDirections) {
        const std::pair<double, double> point{std::clamp(centre.first + di * step, lo, hi),
                                              std::clamp(centre.second + dj * step, lo, hi)};
        const double v = value(point);
        if (v < best_value) {
          best_value = v;
          best = point;
          moved = true;
        }
      }
      if (!moved) step *= 0.5;
    }
    return {best, best_value};
  }

  // The objective at (Rn, Rt) (-): from the cache, or one fast-mode evaluation of every scene;
  // reports progress and stops with Cancelled when asked to.
  double value(const std::pair<double, double>& point) {
    const auto found = cache_.find(point);
    if (found != cache_.end()) return found->second;
    if (progress_.cancelled()) throw Cancelled();
    const double v = calibration_objective(target_, evaluator_.outcomes(point.first, point.second), settings_);
    cache_.emplace(point, v);
    const int n = std::max(settings_.grid_points, 2);
    progress_.report(static_cast<double>(cache_.size()) / static_cast<double>(n * n + 30 * settings_.refine_starts), "fitting");
    return v;
  }

  const FastEvaluator& evaluator_;
  const std::vector<SlopeOutcome>& target_;
  const CalibrationSettings& settings_;
  PartProgress& progress_;
  std::map<std::pair<double, double>, double> cache_;
};

}  // namespace

// Paper 2.2: a bilinear DEM whose nodes follow the flat crest, the planar slope and the flat
// runout zone exactly (the breaks fall inside one cell each).
GroundModel calibration_ground(const CalibrationScene& scene, double angle, const GroundMaterial& material) {
  const double gradient = std::tan(radians(angle));
  const double slope_run = scene.slope_length * std::cos(radians(angle));  // m, horizontal
  const double drop = slope_run * gradient;                                // m
  const double half_width = 0.5 * (scene.sources - 1) * scene.source_spacing + scene.side_margin;
  GridSpec spec;
  spec.width = static_cast<int>(std::ceil((scene.crest_length + slope_run + scene.runout_length) / scene.cell_size)) + 1;
  spec.height = static_cast<int>(std::ceil(2.0 * half_width / scene.cell_size)) + 1;
  spec.geotransform = {-scene.crest_length - 0.5 * scene.cell_size, scene.cell_size, 0.0,
                       half_width + 0.5 * scene.cell_size, 0.0, -scene.cell_size};
  Grid<double> elevation(spec);
  for (int row = 0; row < spec.height; ++row) {
    for (int col = 0; col < spec.width; ++col) {
      const double x = std::clamp(spec.node_x(col), 0.0, slope_run);
      elevation.at(col, row) = kFootElevation + drop - gradient * x;
    }
  }
  return GroundModel(std::move(elevation), Grid<GroundMaterial>(spec, material));
}

// Paper 3.3: release "on a simple and well known configuration": one row across the slope.
std::vector<ReleaseSource> calibration_sources(const CalibrationScene& scene) {
  std::vector<ReleaseSource> sources;
  for (int i = 0; i < scene.sources; ++i) {
    const double y = (i - 0.5 * (scene.sources - 1)) * scene.source_spacing;
    sources.push_back({scene.cell_size, y, false, {}});
  }
  return sources;
}

// Paper 3.4: the stochastic runs; every run's line is kept for its jump height.
SlopeOutcome simulate_slope(const GroundModel& ground, const std::vector<ReleaseSource>& sources,
                            const TrajectoryModel& model, const CalibrationSettings& settings, std::uint64_t runs,
                            Progress* progress) {
  RockfallSettings run;
  run.rock = settings.rock;
  run.stochastic = settings.stochastic;
  run.runs_per_source = runs;
  run.seed = settings.seed;
  run.threads = settings.threads;
  run.saved_trajectories = sources.size() * runs;
  const RockfallResult result = run_rockfall(ground, sources, model, run, progress);
  std::vector<double> jumps;
  for (const TrajectoryLine& line : result.lines) jumps.push_back(largest_jump(ground, line));
  SlopeOutcome outcome;
  outcome.median_runout = median(result.runouts);
  outcome.median_jump = median(jumps);
  const auto left = result.stop_counts[static_cast<std::size_t>(StopReason::left_dem)];
  outcome.left_share = result.trajectories == 0 ? 0.0 : static_cast<double>(left) / static_cast<double>(result.trajectories);
  return outcome;
}

// docs/calibration.md, "Objective": relative error against a floor of one rock diameter (-).
double runout_error(const SlopeOutcome& target, const SlopeOutcome& fast, const CalibrationSettings& settings) {
  return (fast.median_runout - target.median_runout) / std::max(target.median_runout, settings.rock.axes.maxCoeff());
}

// docs/calibration.md, "Objective": sum over slopes of squared relative errors (-).
double calibration_objective(const std::vector<SlopeOutcome>& target, const std::vector<SlopeOutcome>& fast,
                             const CalibrationSettings& settings) {
  const double scale = settings.rock.axes.maxCoeff();  // m: the smallest meaningful runout or jump
  double sum = 0.0;
  for (std::size_t s = 0; s < target.size() && s < fast.size(); ++s) {
    const double runout = runout_error(target[s], fast[s], settings);
    const double jump = (fast[s].median_jump - target[s].median_jump) / std::max(target[s].median_jump, scale);
    sum += runout * runout + settings.jump_weight * jump * jump;
  }
  return sum;
}

// The class and the default vegetation of `table`; InputError when either is missing.
std::pair<const LithologyClass*, const VegetationClass*> class_and_vegetation(const MaterialsTable& table, int code) {
  const LithologyClass* lithology = table.find_lithology(code);
  if (lithology == nullptr) throw InputError("no lithology class " + std::to_string(code) + " in the materials table");
  const VegetationClass* vegetation = table.find_vegetation(table.default_vegetation);
  if (vegetation == nullptr) {
    throw InputError("the default vegetation class " + std::to_string(table.default_vegetation) +
                     " is not in the materials table");
  }
  return {lithology, vegetation};
}

// Paper 3.3, last paragraph: the reference model on "a simple and well known configuration".
std::vector<SlopeOutcome> reference_outcomes(const MaterialsTable& table, int code, const TrajectoryModel& reference,
                                             const CalibrationSettings& settings, Progress* progress) {
  const auto [lithology, vegetation] = class_and_vegetation(table, code);
  const GroundMaterial material = GroundMaterial::from(*lithology, vegetation->deperdition);
  const std::vector<ReleaseSource> sources = calibration_sources(settings.scene);
  std::vector<SlopeOutcome> target;
  const double slopes = static_cast<double>(settings.scene.slope_angles.size());
  for (std::size_t s = 0; s < settings.scene.slope_angles.size(); ++s) {
    const double angle = settings.scene.slope_angles[s];
    PartProgress part(progress, static_cast<double>(s) / slopes, static_cast<double>(s + 1) / slopes,
                      "class " + std::to_string(code) + ", " + std::to_string(std::lround(angle)) + " deg, reference ");
    target.push_back(simulate_slope(calibration_ground(settings.scene, angle, material), sources, reference, settings,
                                    settings.runs_per_source, &part));
  }
  return target;
}

// Paper 3.3, last paragraph: the fast mode "fine tuned" to the reference's outcomes.
ClassCalibration fit_fast_mode(const MaterialsTable& table, int code, const std::vector<SlopeOutcome>& target,
                               const CalibrationSettings& settings, Progress* progress) {
  const auto [lithology, vegetation] = class_and_vegetation(table, code);
  const auto start = std::chrono::steady_clock::now();
  ClassCalibration calibration;
  calibration.code = code;
  calibration.name = lithology->name;
  calibration.restitution_normal_before = calibration.restitution_normal = lithology->restitution_normal;
  calibration.restitution_tangential_before = calibration.restitution_tangential = lithology->restitution_tangential;
  const std::vector<ReleaseSource> sources = calibration_sources(settings.scene);
  const FastEvaluator evaluator(*lithology, vegetation->deperdition, sources, settings);
  const std::vector<SlopeOutcome> before =
      evaluator.outcomes(lithology->restitution_normal, lithology->restitution_tangential);
  PartProgress part(progress, 0.0, 1.0, "class " + std::to_string(code) + ", ");
  calibration.fitted = std::any_of(target.begin(), target.end(),
                                   [&](const SlopeOutcome& t) { return t.median_runout >= settings.min_runout; });
  if (calibration.fitted) {
    CoefficientSearch search(evaluator, target, settings, part);
    std::tie(calibration.restitution_normal, calibration.restitution_tangential) =
        search.minimise({lithology->restitution_normal, lithology->restitution_tangential});
    calibration.evaluations = search.evaluations();
  }
  const std::vector<SlopeOutcome> after =
      evaluator.outcomes(calibration.restitution_normal, calibration.restitution_tangential);
  calibration.objective_before = calibration_objective(target, before, settings);
  calibration.objective_after = calibration_objective(target, after, settings);
  for (std::size_t s = 0; s < target.size() && s < settings.scene.slope_angles.size(); ++s) {
    calibration.slopes.push_back({settings.scene.slope_angles[s], target[s], before[s], after[s]});
  }
  calibration.fit_seconds = seconds_since(start);
  part.report(1.0, "fitted");
  return calibration;
}

// Paper 3.3, last paragraph, for every chosen class against the full model.
CalibrationResult calibrate_fast_mode(const MaterialsTable& table, const std::vector<int>& codes,
                                      const CalibrationSettings& settings, Progress* progress) {
  std::vector<int> chosen = codes;
  if (chosen.empty()) {
    for (const LithologyClass& lithology : table.lithology) chosen.push_back(lithology.code);
  }
  for (int code : chosen) class_and_vegetation(table, code);
  CalibrationResult result;
  result.materials = table;
  const FullModel full(settings.full);
  const double count = static_cast<double>(chosen.size());
  for (std::size_t i = 0; i < chosen.size(); ++i) {
    // The reference runs take about 80 % of a class's time, the fit the rest.
    const double first = static_cast<double>(i);
    PartProgress reference_part(progress, first / count, (first + 0.8) / count, "");
    PartProgress fit_part(progress, (first + 0.8) / count, (first + 1.0) / count, "");
    const auto reference_start = std::chrono::steady_clock::now();
    const std::vector<SlopeOutcome> target = reference_outcomes(table, chosen[i], full, settings, &reference_part);
    const double reference_seconds = seconds_since(reference_start);
    ClassCalibration calibration = fit_fast_mode(table, chosen[i], target, settings, &fit_part);
    calibration.reference_seconds = reference_seconds;
    for (LithologyClass& lithology : result.materials.lithology) {
      if (lithology.code != chosen[i]) continue;
      lithology.restitution_normal = calibration.restitution_normal;
      lithology.restitution_tangential = calibration.restitution_tangential;
    }
    result.classes.push_back(std::move(calibration));
  }
  if (progress != nullptr) progress->report(1.0, "calibrated");
  return result;
}

}  // namespace talus
