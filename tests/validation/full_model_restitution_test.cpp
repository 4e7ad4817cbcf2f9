// Full model (paper 2.1, 2.2, 3.3) against an independent reference: a sphere dropped vertically
// on flat ground of one class rebounds with the restitution that the piston law implies. The
// reference integrates m z'' = sum p(d_i) A - m g in one dimension with a tiny fixed step over
// the same lattice pistons under the sphere, each compressed to where the sphere's profile
// reaches it (d_i = z_ground - (z - sqrt(R^2 - rho_i^2))), through StressCycle and press()
// (tested on their own). With the sphere centred over a lattice point and no friction, the
// piston forces' horizontal parts cancel and their vertical parts are p A, so the two must agree.
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "full_model_scenes.hpp"
#include "talus/ground/stress_cycle.hpp"
#include "talus/rockfall/full_model.hpp"
#include "talus/rockfall/implicit_shape.hpp"

namespace talus {
namespace {

using testing_ground::Recorder;

constexpr double kG = 9.81;

// Vertical speed (m/s) at which a sphere leaving the ground at `impact` m/s downwards, its
// centre at `touch` metres above the unloaded ground, comes back up through that height: the
// quasi-static piston carpet of the reference, velocity Verlet with a fixed step of dt s.
double reference_rebound(const StressCycle& cycle, double radius, double spacing, double mass, double impact,
                         double dt) {
  struct ReferencePiston {
    double rho_squared;  // m2: squared horizontal distance to the sphere's axis
    PistonState state;
  };
  std::vector<ReferencePiston> pistons;
  const int reach = static_cast<int>(std::ceil(radius / spacing));
  for (int i = -reach; i <= reach; ++i) {
    for (int j = -reach; j <= reach; ++j) {
      const double rho_squared = (i * i + j * j) * spacing * spacing;
      if (rho_squared < radius * radius) pistons.push_back({rho_squared, PistonState{}});
    }
  }
  const double area = spacing * spacing;  // flat ground: s^2 / n_z with n_z = 1
  const auto acceleration = [&](double height) {  // height: centre above the touch height R (m)
    double force = 0.0;
    for (ReferencePiston& piston : pistons) {
      const double pushed_to = -(height + radius - std::sqrt(radius * radius - piston.rho_squared));
      force += press(cycle, piston.state, pushed_to) * area;
    }
    return force / mass - kG;
  };
  double z = 0.0;
  double v = -impact;
  double a = acceleration(z);
  while (true) {
    const double v_half = v + 0.5 * dt * a;
    const double z_next = z + dt * v_half;
    a = acceleration(z_next);
    const double v_next = v_half + 0.5 * dt * a;
    if (v_next > 0.0 && z_next >= 0.0) {
      // Back through the touch height within this step: interpolate the speed there.
      const double share = (0.0 - z) / (z_next - z);
      return v + share * (v_next - v);
    }
    z = z_next;
    v = v_next;
  }
}

TEST(FullModelRestitution, SphereDroppedOnFlatGroundReboundsAsThePistonLawImplies) {
  const double ground_z = 100.0;
  const GroundMaterial soil = full_model_scenes::talus_soil(0.0);  // no friction: a vertical 1D problem
  const GroundModel model = full_model_scenes::inclined_plane(20, 20, 5.0, ground_z, 0.0, soil);
  const PerturbedGround ground(model, nullptr);
  const Rock rock = full_model_scenes::sphere(1.0);
  const double radius = 0.5;
  const double drop = 1.0;  // m from the touch height
  FullModelParameters parameters;
  parameters.drag_coefficient = 0.0;
  parameters.max_time = 0.9;  // the first rebound only
  // Centred over lattice point (400, -400): x = 50 m, y = -50 m, spacing 0.125 m.
  const RigidBodyState start = full_model_scenes::released(ground, 50.0, -50.0, radius + drop);
  Recorder recorder;
  FullModel(parameters).run(ground, rock, start, recorder);

  // The contact's end: the first sample moving up; ballistic from there to the touch height.
  const TrajectorySample* leaving = nullptr;
  for (const TrajectorySample& sample : recorder.samples) {
    if (sample.velocity.z() > 0.0) {
      leaving = &sample;
      break;
    }
  }
  ASSERT_NE(leaving, nullptr);
  const double below_touch = ground_z + radius - leaving->position.z();
  const double model_rebound = std::sqrt(leaving->velocity.z() * leaving->velocity.z() - 2.0 * kG * below_touch);
  const double impact = std::sqrt(2.0 * kG * drop);

  const double mass =
      integrate_mass(ImplicitShape(rock, parameters.surface_samples), rock.density, parameters.mass_resolution).mass;
  const double reference = reference_rebound(StressCycle::of(soil), radius, 0.125, mass, impact, 1e-6);
  const double model_restitution = model_rebound / impact;
  const double reference_restitution = reference / impact;
  const double error = std::abs(model_restitution - reference_restitution) / reference_restitution;
  std::printf("restitution: model %.5f, reference %.5f, relative difference %.2e\n", model_restitution,
              reference_restitution, error);
  // Tolerance 2% (issue 4); the horizontal drift must stay nil by symmetry (1e-9 m).
  EXPECT_LT(error, 0.02);
  EXPECT_NEAR(leaving->position.x(), 50.0, 1e-9);
  EXPECT_NEAR(leaving->position.y(), -50.0, 1e-9);
}

}  // namespace
}  // namespace talus
