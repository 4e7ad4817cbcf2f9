// Dam breaks against their closed forms (docs/references.md, "Mud flow"): Faccanoni & Mangeney (2012)
// on an incline with Coulomb friction, and Ritter's frictionless flat case (issue 5: front
// position within 5% at three times).
//
// The front. The analytic front is where the depth vanishes; the SPH flow's leading particles
// carry finite masses whose kernels spread as the layer thins, so its very tip, or any one small
// iso-depth, moves by a particle spacing from one particle to the next. The front compared here
// is the mass front: the position beyond which a volume q = 0.2 m3 per metre of width lies (a
// fifth of the release depth h0 = 1 m over one metre). It integrates the depth over the tip, so
// it is exact for particles (they carry the mass), and its analytic value follows from the
// rarefaction fan h = (2c - x/t + m0 t/2)^2 / (9 gz):
//   int_x^x_f h dx = t (2c - x/t + m0 t/2)^3 / (27 gz)  =>  x_q = x_f - t^(2/3) (27 gz q)^(1/3).
// It lies inside the fan at the times used (the fan's tail is at (m0 t/2 - c) t).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mudflow_scenes.hpp"

namespace talus {
namespace {

constexpr double kG = 9.81;       // m/s2
constexpr double kRho = 2000.0;   // kg/m3
constexpr double kH0 = 1.0;       // m: release depth normal to the ground
constexpr double kQ = 0.2;        // m3/m: volume beyond the mass front

// Faccanoni & Mangeney's mass front (m along the slope) at time t for slope phi and bed
// friction angle delta (rad).
double analytic_mass_front(double phi, double delta, double t) {
  const double gz = kG * std::cos(phi);
  const double m0 = gz * (std::tan(phi) - std::tan(delta));
  const double c = std::sqrt(gz * kH0);
  const double front = 2.0 * c * t + 0.5 * m0 * t * t;
  return front - std::pow(t, 2.0 / 3.0) * std::cbrt(27.0 * gz * kQ);
}

// The dam breaks' settings: uniform particles of particle_size (m) for duration (s), Coulomb
// friction coefficient mu (-).
MudflowSettings dam_break_settings(double particle_size, double duration, double mu) {
  MudflowSettings s;
  s.duration = duration;
  s.particle_size = particle_size;
  s.adaptive = false;
  s.rheology.rheology = Rheology::coulomb;
  s.rheology.friction = mu;
  s.rheology.internal_viscosity = 0.01;  // m2/s: the closed forms have none
  s.stop_energy_fraction = 0.0;
  s.release_thickness = ReleaseThickness::vertical;  // the scene's depths are heights of vertical columns
  s.snapshot_interval = 0.5;
  s.curvature = false;  // planes: no curvature, no need to look for it
  s.threads = 1;        // the result is the same at any count (mudflow_thread_determinism_test.cpp)
  return s;
}

TEST(MudflowDamBreak, FrontOnAnInclineFollowsFaccanoniMangeney) {
  // phi = 30 deg, delta = 20 deg: friction takes 40% of gravity's pull (m0 = 1.81 m/s2 against
  // g sin(phi) = 4.9 m/s2). A 16 m reservoir, 12 m wide, on a plane 22 m wide: on the incline
  // the flow outruns its spreading sides, so the band |y| < 3 m stays one-dimensional (a 26 m or
  // 40 m wide reservoir gives the same fronts to 1%).
  const double phi = std::numbers::pi / 6.0, delta = std::numbers::pi / 9.0;
  const GridSpec spec = mudflow_scenes::grid(66, 22, 1.0, -21.0, 11.0);
  const GroundModel ground = mudflow_scenes::ground(spec, [&](double x, double) { return 100.0 - std::tan(phi) * x; });
  const ReleaseSet release = mudflow_scenes::release(spec, [&](double x, double y) {
    return (x > -16.0 && x < 0.0 && std::abs(y) < 6.0) ? kH0 / std::cos(phi) : 0.0;
  });
  const MudflowResult result = run_mudflow(ground, release, nullptr, dam_break_settings(0.2, 4.5, std::tan(delta)), nullptr);
  for (const double t : {3.5, 4.0, 4.5}) {
    const ParticleSnapshot* shot = mudflow_scenes::snapshot_at(result, t);
    ASSERT_NE(shot, nullptr) << t;
    const double expected = analytic_mass_front(phi, delta, t);
    const double front = mudflow_scenes::mass_front(*shot, phi, 3.0, 6.0, kQ, kRho);
    // 5% (issue 5). Measured at particle size 0.2 m: -3.3%, -3.1%, -2.9% (other seeds and
    // domains: -1.9% to -3.7%); the SPH front lags by about one smoothing radius, 0.5-1 m, from
    // the smoothed start of the dam break.
    EXPECT_NEAR(front, expected, 0.05 * expected) << "t = " << t << " s";
  }
}

TEST(MudflowDamBreak, FrontOnFlatGroundFollowsRitter) {
  // A 6 m wide frictionless channel between steep walls (20 m high, one 0.25 m cell wide), which
  // keeps the flow one-dimensional (on flat ground a free strip's sides spread into the slow,
  // thin front): the band is the whole channel, the columns pressed onto the walls' faces
  // included. A 30 m reservoir: the wave from its back reaches the fan's tail at 30 m / 2c = 4.8 s
  // and the mass front later still.
  const GridSpec spec = mudflow_scenes::grid(320, 40, 0.25, -35.0, 5.0);
  const GroundModel ground =
      mudflow_scenes::ground(spec, [](double, double y) { return std::abs(y) > 3.0 ? 120.0 : 100.0; });
  const ReleaseSet release = mudflow_scenes::release(
      spec, [](double x, double y) { return (x > -30.0 && x < 0.0 && std::abs(y) < 3.0) ? kH0 : 0.0; });
  const MudflowResult result = run_mudflow(ground, release, nullptr, dam_break_settings(0.25, 6.0, 0.0), nullptr);
  for (const double t : {4.0, 5.0, 6.0}) {
    const ParticleSnapshot* shot = mudflow_scenes::snapshot_at(result, t);
    ASSERT_NE(shot, nullptr) << t;
    const double expected = analytic_mass_front(0.0, 0.0, t);
    const double front = mudflow_scenes::mass_front(*shot, 0.0, 5.0, 6.0, kQ, kRho);
    // 5% (issue 5). Measured: -0.8%, -1.2%, -0.9% (other seeds: within 3%; at 2-3 s the front
    // still lags by up to 10%, about one smoothing radius).
    EXPECT_NEAR(front, expected, 0.05 * expected) << "t = " << t << " s";
  }
}

}  // namespace
}  // namespace talus
