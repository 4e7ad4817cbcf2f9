// The stress cycle of one soil piston (paper 2.1, fig. 2; docs/architecture.md section 2). Pressure p (Pa)
// against compression d (m, along the piston's axis, into the ground):
//   elastic loading      p = k1 d                       while p < yield pressure Y,
//   plastic loading      p = Y + k2 (d - Y / k1)        beyond it (k2 < k1),
//   unloading/reloading  p = p_max - k3 (d_max - d)     below the largest compression d_max
//                                                       reached so far (k3 > k1), and p >= 0.
// The piston never expands above its residual footprint d_res = d_max - p_max / k3: a piston
// whose top is pushed to a smaller compression is out of contact (p = 0, d = d_res). Loading
// past d_max follows the loading curve again. The energy dissipated per unit cross-section is
// the area of the closed loop, L(d_max) - p_max^2 / (2 k3), L the loading curve's integral: it
// depends on d_max only, so it is exact whatever path the compression took.
// Robustness: an unloading slope given below the loading slopes is raised to them (k3 is used as
// max(k3, k1, k2), k2 counting only when Y is finite), so footprints and loop areas are never
// negative; an infinite Y gives purely elastic loading; k1 = 0 means no ground resistance
// (p = 0 at every compression). Slopes and Y are taken as >= 0.
#pragma once

#include "talus/ground/ground_model.hpp"

namespace talus {

struct StressCycle {
  double elastic_slope = 0;    // k1 (Pa/m)
  double yield_pressure = 0;   // Y (Pa); infinite: purely elastic loading
  double plastic_slope = 0;    // k2 (Pa/m)
  double unloading_slope = 0;  // k3 (Pa/m) >= k1; k3 = k1 with infinite Y: no dissipation at all

  // The material's k1, Y, k2 and k3, with k3 already raised as in the header comment.
  static StressCycle of(const GroundMaterial& material);

  double loading_pressure(double compression) const;           // Pa, on the loading curve
  double loading_work(double compression) const;               // J/m2: integral of the loading curve from 0
  double residual_compression(double max_compression) const;   // m: the footprint d_res
  double loop_energy(double max_compression) const;            // J/m2 dissipated: the loop's area
};

// What one piston remembers between steps (paper 2.2: "each piston will store the local
// stress history").
struct PistonState {
  double compression = 0;       // d (m), >= the residual footprint
  double max_compression = 0;   // d_max (m)
  double max_pressure = 0;      // p_max (Pa) = loading_pressure(d_max)
};

// Moves the piston to the compression its top is pushed to (m; values below the residual
// footprint, and NaN, leave it at the footprint, out of contact) and returns its pressure
// (Pa, >= 0).
double press(const StressCycle& cycle, PistonState& state, double pushed_to);
// Pressure (Pa) of the piston in its current state, without changing it.
double pressure(const StressCycle& cycle, const PistonState& state);
// Elastic energy the piston would give back if unloaded to its footprint (J/m2): p^2 / (2 k3).
double stored_energy(const StressCycle& cycle, const PistonState& state);
// Energy dissipated so far (J/m2): cycle.loop_energy(state.max_compression).
double dissipated_energy(const StressCycle& cycle, const PistonState& state);

}  // namespace talus
