// Calibration of the fast bounce mode against the full model (paper 3.3, "Fast Bounce mode",
// last paragraph: "fine tune the accelerated mode on a simple and well known configuration,
// then use it as a coarse model for complex configurations"). For each lithology class, a few
// planar slopes followed by flat ground, all of that class, are simulated with the full model
// (Monte Carlo runs of paper 3.4); the fast mode's restitution_normal and
// restitution_tangential of the class are then fitted so that its median runout on every slope
// matches the full model's. Scenes, objective, search and measured figures: docs/calibration.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "talus/core/progress.hpp"
#include "talus/ground/ground_model.hpp"
#include "talus/ground/materials.hpp"
#include "talus/rockfall/fast_bounce.hpp"
#include "talus/rockfall/full_model.hpp"
#include "talus/rockfall/monte_carlo.hpp"
#include "talus/rockfall/trajectory_model.hpp"

namespace talus {

// The simple slope of one calibration run: flat ground above the crest, a planar slope falling
// towards +x, flat ground below it; release points in a row across the slope just below the
// crest. Local metric coordinates, the crest along x = 0.
struct CalibrationScene {
  std::vector<double> slope_angles = {30.0, 40.0};  // deg: one scene per angle
  double slope_length = 120.0;     // m, measured along the slope
  double runout_length = 150.0;    // m of flat ground below the foot of the slope
  double crest_length = 10.0;      // m of flat ground above the crest
  double side_margin = 50.0;       // m of ground beyond the outer release points, on each side
  double cell_size = 5.0;          // m, DEM cell
  int sources = 12;                // release points across the slope
  double source_spacing = 5.0;     // m between neighbouring release points
};

struct CalibrationSettings {
  CalibrationScene scene;
  Rock rock;                             // the nominal rock of both models
  StochasticParameters stochastic;       // the run-to-run variation, as in `talus rockfall`
  std::uint64_t runs_per_source = 2;     // reference (full model) runs per release point and slope
  std::uint64_t fast_runs_per_source = 8;  // fast-mode runs per release point and slope: the fast
                                         // mode is cheap, and more runs smooth its medians
  std::uint64_t seed = 1;                // the same draws for every evaluation (common random numbers)
  int threads = 0;                       // 0: OpenMP's default
  FastBounceParameters fast;
  FullModelParameters full;
  double jump_weight = 0.1;              // weight of the jump-height term of the objective (-)
  double min_runout = 10.0;              // m: a class whose reference median runout is shorter than
                                         // this on every slope (the rocks hardly move) is not
                                         // fitted and keeps the table's coefficients
  double restitution_min = 0.02;         // search box of both coefficients (-)
  double restitution_max = 0.98;         // (-)
  int grid_points = 9;                   // coarse grid points per coefficient (>= 2)
  int refine_starts = 4;                 // the local refinement starts from this many best grid points
  double refine_step = 0.005;            // the local refinement stops below this step (-)
};

// The medians one model gives on one scene.
struct SlopeOutcome {
  double median_runout = 0;   // m: median over runs of the horizontal path length (RockfallResult::runouts)
  double median_jump = 0;     // m: median over runs of the largest height of the centre above the
                              // unperturbed ground after release (samples of each run's line)
  double left_share = 0;      // -: share of the runs that left the scene (stopped by left_dem)
};

// One slope of one class: the full model's target and the fast mode before and after fitting.
struct SlopeComparison {
  double angle = 0;           // deg
  SlopeOutcome full;
  SlopeOutcome fast_before;   // with the table's coefficients
  SlopeOutcome fast_after;    // with the fitted coefficients
};

struct ClassCalibration {
  int code = 0;
  std::string name;
  double restitution_normal_before = 0, restitution_tangential_before = 0;  // the table's (-)
  double restitution_normal = 0, restitution_tangential = 0;                // fitted (-)
  double objective_before = 0, objective_after = 0;                         // (-)
  bool fitted = false;                   // false: the rocks hardly moved on every slope (min_runout),
                                         // the table's coefficients are kept
  int evaluations = 0;                   // fast-mode evaluations of the objective
  double reference_seconds = 0;          // wall time of the reference runs (s; calibrate_fast_mode)
  double fit_seconds = 0;                // wall time of the fit (s)
  std::vector<SlopeComparison> slopes;
};

struct CalibrationResult {
  MaterialsTable materials;              // the input table with the fitted coefficients
  std::vector<ClassCalibration> classes; // in the order of the requested codes
};

// The ground of one calibration scene (paper 2.2: bilinear DEM) with `material` at every node.
GroundModel calibration_ground(const CalibrationScene& scene, double angle, const GroundMaterial& material);
// The release points of a calibration scene: one cell below the crest, centred across the slope.
std::vector<ReleaseSource> calibration_sources(const CalibrationScene& scene);

// `runs` Monte Carlo runs of `model` per source on one scene (paper 3.4) and their medians.
SlopeOutcome simulate_slope(const GroundModel& ground, const std::vector<ReleaseSource>& sources,
                            const TrajectoryModel& model, const CalibrationSettings& settings, std::uint64_t runs,
                            Progress* progress);

// The objective (docs/calibration.md): over slopes, the squared relative error of the fast
// mode's median runout plus jump_weight times that of its median jump height; relative errors
// are taken against max(target, rock diameter) so that a target of rocks that barely move stays
// finite.
double calibration_objective(const std::vector<SlopeOutcome>& target, const std::vector<SlopeOutcome>& fast,
                             const CalibrationSettings& settings);
// The relative error of the fast mode's median runout in the objective (-): against
// max(target, rock diameter).
double runout_error(const SlopeOutcome& target, const SlopeOutcome& fast, const CalibrationSettings& settings);

// The medians of `reference` (the full model; tests pass the fast mode) on every scene of
// `settings`, covered by lithology class `code` of `table` and its default vegetation class.
// Throws InputError for a code or default vegetation class missing from the table, Cancelled
// when `progress` asks to stop.
std::vector<SlopeOutcome> reference_outcomes(const MaterialsTable& table, int code, const TrajectoryModel& reference,
                                             const CalibrationSettings& settings, Progress* progress);

// Fits the fast mode's coefficients of class `code` of `table` to `target` (one outcome per
// scene of `settings`), the table's coefficients being one of the candidates; leaves them as
// they are when the target's rocks hardly move on every slope (min_runout). Same exceptions.
ClassCalibration fit_fast_mode(const MaterialsTable& table, int code, const std::vector<SlopeOutcome>& target,
                               const CalibrationSettings& settings, Progress* progress);

// Calibrates every class of `codes` (all classes of the table when empty) against FullModel.
CalibrationResult calibrate_fast_mode(const MaterialsTable& table, const std::vector<int>& codes,
                                      const CalibrationSettings& settings, Progress* progress);

}  // namespace talus
