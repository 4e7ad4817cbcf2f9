// A column of mud at rest in a basin (issue 5: pressures within 3% of rho g depth).
//
// The basin: a flat floor 12 m x 12 m with walls of slope 20 degrees. The mud is released at the
// level it holds at rest, jittered (release_particles.hpp), and settles. The known free surface:
// flat over the floor, and on the walls the shallow-flow equilibrium, where the depth normal to
// the ground thins by tan(theta) per metre of slope (Savage & Hutter 1989; docs/mudflow.md
// "Ground contact"), i.e. the vertical thickness by k = tan(theta) (1 + tan^2(theta)) per metre
// of horizontal distance d from the floor: H - k d. The level H follows from the released volume:
//   V = L^2 H + 2 L H^2 / k + 4 H^3 / (3 k^2)   (floor, four wall strips, four corners).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mudflow_scenes.hpp"

namespace talus {
namespace {

constexpr double kG = 9.81;       // m/s2
constexpr double kRho = 2000.0;   // kg/m3

TEST(MudflowColumnAtRest, BasalPressureIsHydrostatic) {
  const double half_floor = 6.0, wall_slope = std::tan(20.0 * std::numbers::pi / 180.0), level = 2.0;
  const double k = wall_slope * (1.0 + wall_slope * wall_slope);
  const auto beyond_floor = [&](double x, double y) { return std::max(0.0, std::max(std::abs(x), std::abs(y)) - half_floor); };
  const GridSpec spec = mudflow_scenes::grid(50, 50, 0.5, -12.5, 12.5);
  const GroundModel ground =
      mudflow_scenes::ground(spec, [&](double x, double y) { return wall_slope * beyond_floor(x, y); });
  const ReleaseSet release =
      mudflow_scenes::release(spec, [&](double x, double y) { return level - k * beyond_floor(x, y); });

  MudflowSettings s;
  s.duration = 20.0;
  s.particle_size = 0.5;
  s.adaptive = false;
  s.threads = 1;
  s.rheology.rheology = Rheology::viscous;  // no yield stress: the surface can level out
  s.rheology.viscosity = 1000.0;            // Pa s: damps the sloshing within seconds
  s.rheology.internal_viscosity = 0.1;
  s.stop_energy_fraction = 0.0;
  s.stop_speed = 0.0;                       // nothing deposits: every column keeps settling
  s.snapshot_interval = s.duration;
  const MudflowResult result = run_mudflow(ground, release, nullptr, s, nullptr);

  const double length = 2.0 * half_floor, volume = result.released_volume;
  double low = 0.0, high = 10.0;
  for (int k_iteration = 0; k_iteration < 200; ++k_iteration) {
    const double h = 0.5 * (low + high);
    const double held = length * length * h + 2.0 * length * h * h / k + 4.0 * h * h * h / (3.0 * k * k);
    (held > volume ? high : low) = h;
  }
  const double surface = 0.5 * (low + high);
  ASSERT_EQ(result.snapshots.back().time, s.duration);
  const ParticleSnapshot& shot = result.snapshots.back();
  int interior = 0;
  for (std::size_t i = 0; i < shot.x.size(); ++i) {
    // Interior: two metres (more than one smoothing radius, 1.2 m) inside the floor's edge.
    if (std::max(std::abs(shot.x[i]), std::abs(shot.y[i])) > half_floor - 2.0) continue;
    ++interior;
    const double pressure = kRho * kG * shot.depth[i];  // Pa: flat floor, cos(theta) = 1
    // 3% (issue 5). Measured: at most 2.1%, -0.6% on average over the interior columns.
    EXPECT_NEAR(pressure, kRho * kG * surface, 0.03 * kRho * kG * surface) << i;
  }
  EXPECT_GT(interior, 200);
  // Settled: the kinetic energy has fallen below 5% of its peak (measured 2.6%).
  EXPECT_LT(result.history.back().kinetic_energy, 0.05 * result.peak_kinetic_energy);
}

}  // namespace
}  // namespace talus
