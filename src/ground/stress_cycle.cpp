// The stress cycle of one soil piston (paper 2.1, fig. 2): elastic then plastic loading,
// unloading and reloading along one steeper line from the largest compression, the residual
// footprint, and the energy the loop dissipates.
#include "talus/ground/stress_cycle.hpp"

#include <algorithm>
#include <cmath>

namespace talus {
namespace {

// k3 as the cycle uses it (Pa/m): never less steep than the loading curve, so that the unloading
// line stays below it and reaches p = 0 at a footprint >= 0 (header comment).
double unloading_slope_used(const StressCycle& cycle) {
  const double plastic = std::isfinite(cycle.yield_pressure) ? cycle.plastic_slope : 0.0;
  return std::max({cycle.unloading_slope, cycle.elastic_slope, plastic});
}

// Paper fig. 2, end of the cycle: the compression (m) where the unloading line from
// (d_max, p_max) reaches p = 0, slope k3 (Pa/m). Without pressure the piston keeps d_max.
double footprint(double max_compression, double max_pressure, double k3) {
  return max_pressure > 0.0 ? max_compression - max_pressure / k3 : max_compression;
}

// Elastic energy (J/m2) released along the unloading line from pressure p (Pa) to 0: p^2 / (2 k3).
double unloading_work(double pressure_value, double k3) {
  return pressure_value > 0.0 ? pressure_value * pressure_value / (2.0 * k3) : 0.0;
}

// Paper fig. 2, unloading/reloading branch: p = p_max - k3 (d_max - d) (Pa) for a compression d
// (m) above the footprint, 0 at or below it.
double unloading_pressure(const PistonState& state, double compression, double k3) {
  if (!(compression > footprint(state.max_compression, state.max_pressure, k3))) return 0.0;
  return std::max(0.0, state.max_pressure - k3 * (state.max_compression - compression));
}

}  // namespace

StressCycle StressCycle::of(const GroundMaterial& material) {
  StressCycle cycle;
  cycle.elastic_slope = material.elastic_slope;
  cycle.yield_pressure = material.yield_pressure;
  cycle.plastic_slope = material.plastic_slope;
  cycle.unloading_slope = material.unloading_slope;
  cycle.unloading_slope = unloading_slope_used(cycle);
  return cycle;
}

// Paper fig. 2, loading curve (Pa): k1 d up to Y, then Y + k2 (d - Y / k1).
double StressCycle::loading_pressure(double compression) const {
  if (!(compression > 0.0) || elastic_slope <= 0.0) return 0.0;
  const double elastic = elastic_slope * compression;
  if (elastic <= yield_pressure) return elastic;
  return yield_pressure + plastic_slope * (compression - yield_pressure / elastic_slope);
}

// Integral of the loading curve from 0 to d (J/m2): the elastic triangle k1 d_y^2 / 2 up to the
// yield compression d_y = Y / k1, then the trapezoid (Y + p(d)) (d - d_y) / 2.
double StressCycle::loading_work(double compression) const {
  if (!(compression > 0.0) || elastic_slope <= 0.0) return 0.0;
  if (elastic_slope * compression <= yield_pressure) return 0.5 * elastic_slope * compression * compression;
  const double yield_compression = yield_pressure / elastic_slope;
  return 0.5 * yield_pressure * yield_compression +
         0.5 * (yield_pressure + loading_pressure(compression)) * (compression - yield_compression);
}

// Paper 2.1: "the difference between the cycle start and the cycle end gives the footprint":
// d_res = d_max - p_max / k3 (m).
double StressCycle::residual_compression(double max_compression) const {
  return footprint(max_compression, loading_pressure(max_compression), unloading_slope_used(*this));
}

// Paper fig. 2, dashed area (J/m2): work of loading to d_max minus the work given back along the
// unloading line, L(d_max) - p_max^2 / (2 k3). Non-negative by construction of k3; the clamp
// only removes rounding in the purely elastic case.
double StressCycle::loop_energy(double max_compression) const {
  const double loaded = loading_work(max_compression);
  return std::max(0.0, loaded - unloading_work(loading_pressure(max_compression), unloading_slope_used(*this)));
}

// Paper 2.2 and 3.3 step 3: the piston's new state and response for the compression its top is
// pushed to. Past d_max the loading curve moves (d_max, p_max) on; below it the piston follows
// the unloading line, and never rises above its footprint.
double press(const StressCycle& cycle, PistonState& state, double pushed_to) {
  if (pushed_to > state.max_compression) {
    state.max_compression = pushed_to;
    state.max_pressure = cycle.loading_pressure(pushed_to);
    state.compression = pushed_to;
    return state.max_pressure;
  }
  const double k3 = unloading_slope_used(cycle);
  const double residual = footprint(state.max_compression, state.max_pressure, k3);
  state.compression = pushed_to > residual ? pushed_to : residual;
  return unloading_pressure(state, state.compression, k3);
}

// Paper fig. 2: the pressure (Pa) of the state's point on the unloading/reloading line (p_max
// at d_max, 0 at the footprint).
double pressure(const StressCycle& cycle, const PistonState& state) {
  return unloading_pressure(state, state.compression, unloading_slope_used(cycle));
}

// Paper fig. 2: the area under the unloading line below the current pressure (J/m2).
double stored_energy(const StressCycle& cycle, const PistonState& state) {
  const double k3 = unloading_slope_used(cycle);
  return unloading_work(unloading_pressure(state, state.compression, k3), k3);
}

// Paper fig. 2, dashed area of the loop closed at the current d_max (J/m2).
double dissipated_energy(const StressCycle& cycle, const PistonState& state) {
  return cycle.loop_energy(state.max_compression);
}

}  // namespace talus
