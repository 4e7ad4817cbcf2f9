// Fast-mode flight against closed forms (docs/references.md, "Rock fall"): free fall and projectile
// without drag within 1e-6 relative; with the sphere's quadratic drag (paper 3.2), the vertical
// fall z(t) = z0 - (v_t^2 / g) ln cosh(g t / v_t) and the terminal velocity
// v_t = sqrt(2 m g / (rho Cx A)) within 1%.
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

Rock sphere(double diameter, double density) {
  Rock rock;
  rock.shape = BlockShape::sphere;
  rock.axes = Eigen::Vector3d::Constant(diameter);
  rock.density = density;
  return rock;
}

// Flat ground at z = 0, `cells` x `cells` cells of `cell` metres.
GroundModel flat_ground(int cells, double cell) {
  return testing_ground::make_ground(testing_ground::local_spec(cells, cells, cell), [](double, double) { return 0.0; },
                                     testing_ground::fast_material(0.5, 0.8, 0.5));
}

// Index of the first sample at a contact (the rock's contact point on the ground, moving down).
std::size_t first_arrival(const Recorder& recorder, double radius) {
  for (std::size_t i = 0; i < recorder.samples.size(); ++i) {
    const TrajectorySample& s = recorder.samples[i];
    if (std::abs(s.jump_height - radius) < 1e-9 && s.velocity.z() < 0.0) return i;
  }
  return recorder.samples.size();
}

// Largest relative error |d_sim - d_exact| / |d_exact| of the displacement from the release over
// the samples before the first contact, for a closed form exact(t).
template <class Exact>
double worst_relative_error(const Recorder& recorder, std::size_t end, const Exact& exact) {
  const Eigen::Vector3d start = recorder.samples.front().position;
  double worst = 0.0;
  for (std::size_t i = 1; i < end; ++i) {
    const TrajectorySample& s = recorder.samples[i];
    const Eigen::Vector3d expected = exact(s.time) - start;
    worst = std::max(worst, (s.position - start - expected).norm() / expected.norm());
  }
  return worst;
}

TEST(RockfallFlight, FreeFallMatchesClosedFormWithin1e6) {
  const GroundModel model = flat_ground(21, 10.0);
  const PerturbedGround ground(model, nullptr);
  const Rock rock = sphere(1.0, 2700.0);
  FastBounceParameters parameters;
  parameters.drag_coefficient = 0.0;
  RigidBodyState start;
  const double drop = 80.0;  // contact point above the ground (m)
  start.position = {100.0, -100.0, drop + 0.5};
  Recorder recorder;
  FastBounce(parameters).run(ground, rock, start, recorder);

  const std::size_t arrival = first_arrival(recorder, 0.5);
  ASSERT_LT(arrival, recorder.samples.size());
  ASSERT_GT(arrival, 20u);  // samples along the fall, at least every 2.5 m
  const auto exact = [&](double t) { return Eigen::Vector3d(100.0, -100.0, drop + 0.5 - 0.5 * kG * t * t); };
  const double error = worst_relative_error(recorder, arrival, exact);
  EXPECT_LT(error, 1e-6);

  const double contact_time = std::sqrt(2.0 * drop / kG);
  const TrajectorySample& hit = recorder.samples[arrival];
  EXPECT_LT(std::abs(hit.time - contact_time) / contact_time, 1e-6);
  EXPECT_LT(std::abs(hit.velocity.z() + kG * contact_time) / (kG * contact_time), 1e-6);
  EXPECT_NEAR(hit.position.z(), 0.5, 1e-9);
  std::printf("free fall: worst relative error %.2e, contact time error %.2e s\n", error,
              std::abs(hit.time - contact_time));
}

TEST(RockfallFlight, ProjectileMatchesClosedFormWithin1e6) {
  const GroundModel model = flat_ground(41, 10.0);
  const PerturbedGround ground(model, nullptr);
  const Rock rock = sphere(1.0, 2700.0);
  FastBounceParameters parameters;
  parameters.drag_coefficient = 0.0;
  RigidBodyState start;
  const Eigen::Vector3d p0(50.0, -50.0, 40.5);
  const Eigen::Vector3d v0(12.0, -7.0, 9.0);
  start.position = p0;
  start.velocity = v0;
  Recorder recorder;
  FastBounce(parameters).run(ground, rock, start, recorder);

  const std::size_t arrival = first_arrival(recorder, 0.5);
  ASSERT_LT(arrival, recorder.samples.size());
  ASSERT_GT(arrival, 20u);
  const auto exact = [&](double t) { return Eigen::Vector3d(p0 + v0 * t - 0.5 * kG * t * t * Eigen::Vector3d::UnitZ()); };
  const double error = worst_relative_error(recorder, arrival, exact);
  EXPECT_LT(error, 1e-6);

  // x(t) = x0 + v0 t, z(t) = z0 + w0 t - g t^2 / 2 reaches the touching height 0.5 m at:
  const double w0 = v0.z();
  const double contact_time = (w0 + std::sqrt(w0 * w0 + 2.0 * kG * (p0.z() - 0.5))) / kG;
  const TrajectorySample& hit = recorder.samples[arrival];
  EXPECT_LT(std::abs(hit.time - contact_time) / contact_time, 1e-6);
  const Eigen::Vector3d landing = exact(contact_time);
  EXPECT_LT((hit.position - landing).norm() / (landing - p0).norm(), 1e-6);
  std::printf("projectile: worst relative error %.2e, contact time error %.2e s\n", error,
              std::abs(hit.time - contact_time));
}

// ln cosh x without overflow.
double log_cosh(double x) { return x + std::log1p(std::exp(-2.0 * x)) - std::numbers::ln2; }

TEST(RockfallFlight, DragFallFollowsClosedFormAndReachesTerminalVelocity) {
  const GroundModel model = flat_ground(3, 100.0);
  const PerturbedGround ground(model, nullptr);
  const double diameter = 0.2;
  const double density = 2700.0;
  const Rock rock = sphere(diameter, density);
  FastBounceParameters parameters;  // rho = 1.225, Cx = 0.1
  parameters.max_time = 150.0;
  const double mass = density * std::numbers::pi * diameter * diameter * diameter / 6.0;
  const double area = std::numbers::pi * 0.25 * diameter * diameter;
  const double terminal = std::sqrt(2.0 * mass * kG / (parameters.air_density * parameters.drag_coefficient * area));
  RigidBodyState start;
  const double z0 = 40000.0;
  start.position = {100.0, -100.0, z0};
  Recorder recorder;
  const StopReason reason = FastBounce(parameters).run(ground, rock, start, recorder);
  ASSERT_EQ(reason, StopReason::max_time);  // still falling after 150 s

  double worst = 0.0;
  for (const TrajectorySample& s : recorder.samples) {
    if (s.time == 0.0) continue;
    const double fallen = terminal * terminal / kG * log_cosh(kG * s.time / terminal);
    const double speed = terminal * std::tanh(kG * s.time / terminal);
    worst = std::max(worst, std::abs((z0 - s.position.z()) - fallen) / fallen);
    worst = std::max(worst, std::abs(-s.velocity.z() - speed) / speed);
  }
  EXPECT_LT(worst, 1e-6);
  const double final_speed = recorder.final_sample.velocity.norm();
  EXPECT_NEAR(recorder.final_sample.time, 150.0, 1e-9);
  EXPECT_LT(std::abs(final_speed - terminal) / terminal, 0.01);
  std::printf("drag: v_t %.4f m/s, final speed %.4f m/s (%.2e), worst error vs closed form %.2e\n", terminal,
              final_speed, std::abs(final_speed - terminal) / terminal, worst);
}

}  // namespace
}  // namespace talus
