// Fast-mode contacts against closed forms (docs/references.md, "Rock fall"): vertical rebounds on flat
// ground reach e^(2n) h0 within 1% (paper 3.3 fast bounce), and a block sliding on a plane
// (Coulomb friction mu) stops if and only if tan(slope) < mu, after v^2 / (2 g (mu cos - sin))
// within 2%. Energy bookkeeping: what the rock loses is what the observer is told.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "synthetic_ground.hpp"
#include "talus/ground/perturbed_ground.hpp"
#include "talus/rockfall/fast_bounce.hpp"

namespace talus {
namespace {

using testing_ground::Recorder;

constexpr double kG = 9.81;
constexpr double kRadius = 0.5;

Rock unit_sphere() {
  Rock rock;
  rock.axes = Eigen::Vector3d::Constant(2.0 * kRadius);
  return rock;
}

TEST(RockfallContact, VerticalReboundsReachRestitutionSquaredPowers) {
  const double restitution = 0.7;
  // Tangential restitution 1 and no vegetation: neutral for a vertical rebound.
  const GroundModel model = testing_ground::make_ground(testing_ground::local_spec(11, 11, 5.0),
                                                        [](double, double) { return 12.0; },
                                                        testing_ground::fast_material(restitution, 1.0, 0.5));
  const PerturbedGround ground(model, nullptr);
  FastBounceParameters parameters;
  parameters.drag_coefficient = 0.0;
  parameters.max_step_length = 0.002;  // dense samples, so the apexes are seen
  parameters.sample_spacing = 0.002;
  RigidBodyState start;
  const double h0 = 5.0;
  start.position = {25.0, -25.0, 12.0 + kRadius + h0};
  Recorder recorder;
  const Rock rock = unit_sphere();
  const StopReason reason = FastBounce(parameters).run(ground, rock, start, recorder);
  EXPECT_EQ(reason, StopReason::at_rest);

  // Apexes: local maxima of the height after the release.
  std::vector<double> apexes;
  const auto& s = recorder.samples;
  for (std::size_t i = 1; i + 1 < s.size(); ++i) {
    if (s[i].position.z() > s[i - 1].position.z() && s[i].position.z() >= s[i + 1].position.z()) {
      apexes.push_back(s[i].position.z() - 12.0 - kRadius);
    }
  }
  ASSERT_GE(apexes.size(), 4u);
  for (int n = 1; n <= 4; ++n) {
    const double expected = std::pow(restitution, 2 * n) * h0;
    const double error = std::abs(apexes[n - 1] - expected) / expected;
    EXPECT_LT(error, 0.01) << "rebound " << n;
    std::printf("rebound %d: %.6f m, expected %.6f m, relative error %.2e\n", n, apexes[n - 1], expected, error);
    EXPECT_NEAR(s[0].position.x(), 25.0, 1e-12);  // stays vertical
  }
  // All the potential energy went into the impacts.
  const double mass = rock.mass();
  EXPECT_NEAR(recorder.deformation_loss() / (mass * kG * h0), 1.0, 1e-6);
  EXPECT_EQ(recorder.friction_loss(), 0.0);
  EXPECT_NEAR(recorder.final_sample.position.z(), 12.0 + kRadius, 1e-9);
}

// A plane descending towards +x at `slope_deg`, friction mu, 400 m long.
GroundModel slope_ground(double slope_deg, double friction) {
  const double tangent = std::tan(slope_deg * std::numbers::pi / 180.0);
  return testing_ground::make_ground(testing_ground::local_spec(81, 11, 5.0),
                                     [tangent](double x, double) { return 300.0 - tangent * x; },
                                     testing_ground::fast_material(0.3, 0.6, friction));
}

struct Slide {
  StopReason reason;
  double distance;   // m along the slope from the release to the stop
  Recorder recorder;
};

// A sphere released on the plane at x = 20 m with speed v0 down the fall line, rolling without
// slip (spin n x v / r) or, with `spinning` false, without spin.
Slide slide(double slope_deg, double friction, double v0, bool spinning = true) {
  const GroundModel model = slope_ground(slope_deg, friction);
  const PerturbedGround ground(model, nullptr);
  const double angle = slope_deg * std::numbers::pi / 180.0;
  RigidBodyState start;
  start.position = {20.0, -25.0, 300.0 - std::tan(angle) * 20.0 + kRadius};
  start.velocity = v0 * Eigen::Vector3d(std::cos(angle), 0.0, -std::sin(angle));
  const Eigen::Vector3d normal(std::sin(angle), 0.0, std::cos(angle));
  if (spinning) start.angular_velocity = normal.cross(start.velocity) / kRadius;
  Slide result{StopReason::max_time, 0.0, {}};
  result.reason = FastBounce().run(ground, unit_sphere(), start, result.recorder);
  result.distance = (result.recorder.final_sample.position - start.position).norm();
  return result;
}

// Azzoni et al. 1995 (docs/references.md, "Rock fall"): a sphere rolling at v0 with rolling friction mu_r stops
// after v0^2 / (2 A g cos t (mu_r - tan t)), A = 5/7; the rolling resistance and the vegetation
// (none here) took its kinetic energy, translation and rotation, and the height it lost. A sphere
// set down without spin starts to roll at 5/7 v0 (angular momentum about the contact point), so
// it stops after 5/7 of that distance, and the friction of the start took 2/7 of its energy.
TEST(RockfallContact, RollingSphereStopsAtAzzonisDistance) {
  struct Case {
    double slope_deg, friction, v0;
  };
  constexpr double kShare = 5.0 / 7.0;
  for (const Case c : {Case{20.0, 0.6, 10.0}, Case{30.0, 0.7, 8.0}, Case{10.0, 0.3, 15.0}, Case{25.0, 0.5, 10.0},
                       Case{5.0, 0.2, 3.0}}) {
    for (const bool spinning : {true, false}) {
      const Slide result = slide(c.slope_deg, c.friction, c.v0, spinning);
      const double angle = c.slope_deg * std::numbers::pi / 180.0;
      ASSERT_LT(std::tan(angle), c.friction);
      const double rolling = spinning ? c.v0 : kShare * c.v0;
      const double expected =
          rolling * rolling / (2.0 * kShare * kG * std::cos(angle) * (c.friction - std::tan(angle)));
      EXPECT_EQ(result.reason, StopReason::at_rest) << c.slope_deg << " deg, mu_r " << c.friction;
      const double error = std::abs(result.distance - expected) / expected;
      EXPECT_LT(error, 0.02) << c.slope_deg << " deg, mu_r " << c.friction << (spinning ? ", rolling" : ", no spin");
      std::printf("slope %.0f deg, mu_r %.2f, v0 %.0f m/s%s: stopped after %.4f m, expected %.4f m, error %.2e\n",
                  c.slope_deg, c.friction, c.v0, spinning ? "" : " (no spin)", result.distance, expected, error);
      const Rock rock = unit_sphere();
      const double drop = result.distance * std::sin(angle);
      const double given = 0.5 * rock.mass() * c.v0 * c.v0 * (spinning ? 1.0 / kShare : 1.0) + rock.mass() * kG * drop;
      EXPECT_NEAR(result.recorder.friction_loss() / given, 1.0, 1e-3);
      EXPECT_LT(result.recorder.deformation_loss(), 1e-9 * given);
    }
  }
}

TEST(RockfallContact, BlockStopsOnlyWhereTanSlopeIsBelowFriction) {
  for (const double slope_deg : {10.0, 20.0, 30.0}) {
    const double tangent = std::tan(slope_deg * std::numbers::pi / 180.0);
    for (const double offset : {-0.02, 0.02}) {
      const double friction = tangent + offset;
      for (const double v0 : {0.0, 4.0}) {
        const Slide result = slide(slope_deg, friction, v0);
        if (offset < 0.0) {
          // Gravity wins: the block slides to the DEM's edge, faster and faster.
          EXPECT_EQ(result.reason, StopReason::left_dem) << slope_deg << " deg, v0 " << v0;
          EXPECT_GT(result.distance, 300.0);
          EXPECT_GT(result.recorder.final_sample.velocity.norm(), v0);
        } else {
          EXPECT_EQ(result.reason, StopReason::at_rest) << slope_deg << " deg, v0 " << v0;
          if (v0 == 0.0) {
            EXPECT_EQ(result.distance, 0.0);
          }
        }
      }
    }
  }
}

}  // namespace
}  // namespace talus
