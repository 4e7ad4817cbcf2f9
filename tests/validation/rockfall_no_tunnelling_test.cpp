// Fast-mode contact detection never lets a rock through the ground (issue 3): on a scene with a
// cliff (a 25 m step between two node columns, which the bilinear ground makes a 79 degree
// face) and a thin ridge (one node row raised 8 m), rocks launched in many directions and at
// many speeds never have their contact point below the ground. The recorded flight between two
// samples is rebuilt by cubic Hermite interpolation of the samples' positions and velocities,
// which is exact for the drag-free parabola, and checked at 100 points per segment; segments in
// contact (the observer was told of friction losses inside them) are on the ground at both ends.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "synthetic_ground.hpp"
#include "talus/ground/perlin_noise.hpp"
#include "talus/ground/perturbed_ground.hpp"
#include "talus/rockfall/fast_bounce.hpp"

namespace talus {
namespace {

constexpr double kCell = 5.0;
constexpr double kCliffX = 150.0;   // nodes at x >= 150 m are 25 m higher
constexpr double kRidgeY = -100.0;  // the node row at y = -100 m is 8 m higher

double scene_elevation(double x, double y) {
  double z = 400.0 - 0.15 * x - 0.05 * y;
  if (x >= kCliffX - 1e-9) z += 25.0;
  if (std::abs(y - kRidgeY) < 1e-9) z += 8.0;
  return z;
}

// Remembers samples and, for each, whether energy was lost since the sample before it.
class SegmentRecorder final : public TrajectoryObserver {
 public:
  void on_sample(const TrajectorySample& sample) override {
    samples.push_back(sample);
    lossy.push_back(lost_since_sample_);
    lost_since_sample_ = false;
  }
  void on_energy_loss(double, double, double friction, double) override {
    if (friction > 0.0) lost_since_sample_ = true;
  }
  void on_stop(const TrajectorySample&, StopReason) override {}
  std::vector<TrajectorySample> samples;
  std::vector<bool> lossy;

 private:
  bool lost_since_sample_ = false;
};

struct Check {
  double worst_penetration = 0.0;  // m, largest depth of the contact point below the ground
  long flight_segments = 0;
  long contact_segments = 0;
  long cliff_face_hits = 0;        // samples on the cliff face
  long ridge_hits = 0;             // samples on the ridge's flanks
  long ridge_crossings = 0;        // trajectories that reached the other side of the ridge
};

void check_trajectory(const PerturbedGround& ground, double radius, const SegmentRecorder& recorder, double ridge_side,
                      Check& check) {
  const auto depth_below = [&](const Eigen::Vector3d& centre) {
    return ground.height(centre.x(), centre.y()) - (centre.z() - radius);
  };
  bool crossed = false;
  for (std::size_t i = 0; i < recorder.samples.size(); ++i) {
    const TrajectorySample& b = recorder.samples[i];
    check.worst_penetration = std::max(check.worst_penetration, depth_below(b.position));
    if ((b.position.y() - kRidgeY) * ridge_side < 0.0) crossed = true;
    if (b.position.x() > kCliffX - kCell && b.position.x() < kCliffX && std::abs(b.jump_height - radius) < 1e-6) {
      ++check.cliff_face_hits;
    }
    if (std::abs(b.position.y() - kRidgeY) < kCell && std::abs(b.jump_height - radius) < 1e-6) ++check.ridge_hits;
    if (i == 0) continue;
    const TrajectorySample& a = recorder.samples[i - 1];
    if (recorder.lossy[i]) {
      ++check.contact_segments;
      continue;
    }
    ++check.flight_segments;
    const double span = b.time - a.time;
    for (int k = 1; k < 100; ++k) {
      const double s = k / 100.0;
      const double h00 = 2 * s * s * s - 3 * s * s + 1, h10 = s * s * s - 2 * s * s + s;
      const double h01 = -2 * s * s * s + 3 * s * s, h11 = s * s * s - s * s;
      const Eigen::Vector3d centre =
          h00 * a.position + h10 * span * a.velocity + h01 * b.position + h11 * span * b.velocity;
      check.worst_penetration = std::max(check.worst_penetration, depth_below(centre));
    }
  }
  if (crossed) ++check.ridge_crossings;
}

// Launches from three places (under the cliff, on its top, beside the ridge) in 36 directions,
// 3 elevations and 3 speeds.
Check launch_all(const PerturbedGround& ground, FastBounceParameters parameters) {
  Rock rock;
  rock.axes = Eigen::Vector3d::Constant(1.0);
  const double radius = 0.5;
  parameters.drag_coefficient = 0.0;
  const FastBounce model(parameters);
  Check check;
  const Eigen::Vector2d places[] = {{kCliffX - 12.0, -150.0}, {kCliffX + 8.0, -160.0}, {100.0, kRidgeY + 9.0}};
  for (const Eigen::Vector2d& place : places) {
    for (int azimuth = 0; azimuth < 36; ++azimuth) {
      for (const double elevation_deg : {0.0, 20.0, 45.0}) {
        for (const double speed : {6.0, 15.0, 30.0}) {
          const double az = azimuth * std::numbers::pi / 18.0;
          const double el = elevation_deg * std::numbers::pi / 180.0;
          RigidBodyState start;
          start.position = {place.x(), place.y(), ground.height(place.x(), place.y()) + radius + 1.0};
          start.velocity = speed * Eigen::Vector3d(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
          SegmentRecorder recorder;
          model.run(ground, rock, start, recorder);
          check_trajectory(ground, radius, recorder, place.y() - kRidgeY, check);
        }
      }
    }
  }
  return check;
}

GroundModel scene(double noise_amplitude) {
  return testing_ground::make_ground(testing_ground::local_spec(60, 60, kCell), scene_elevation,
                                     testing_ground::fast_material(0.5, 0.8, 0.5, 0.0, noise_amplitude));
}

void report(const char* what, const Check& check) {
  std::printf("%s: worst penetration %.3e m over %ld flight and %ld contact segments; %ld samples on the cliff "
              "face, %ld on the ridge, %ld ridge crossings\n",
              what, check.worst_penetration, check.flight_segments, check.contact_segments, check.cliff_face_hits,
              check.ridge_hits, check.ridge_crossings);
}

TEST(RockfallNoTunnelling, CliffAndRidgeAreNeverCrossedBelowTheGround) {
  const GroundModel model = scene(0.0);
  const PerturbedGround ground(model, nullptr);
  const Check check = launch_all(ground, FastBounceParameters{});
  report("no noise", check);
  EXPECT_LT(check.worst_penetration, 1e-6);
  EXPECT_GT(check.flight_segments, 5000);
  EXPECT_GT(check.cliff_face_hits, 50);   // rocks do hit the face,
  EXPECT_GT(check.ridge_hits, 50);        // land on the ridge
  EXPECT_GT(check.ridge_crossings, 30);   // and cross it
}

// With 0.3 m of Perlin roughness (paper 3.4) on top, ground checks every metre cannot see every
// bump of the noise (its finest octave has a 1/8 m lattice): a flight may graze a bump between
// two checks. The DEM's creases are still never crossed, and what the noise can hide stays
// below half its amplitude (8 cm of 30 cm here).
TEST(RockfallNoTunnelling, NoiseBumpsHideOnlyAFractionOfTheirAmplitude) {
  const double amplitude = 0.3;
  const GroundModel model = scene(amplitude);
  PerlinParameters noise_parameters;
  noise_parameters.base_frequency = 1.0;
  noise_parameters.amplitude = 1.0;
  noise_parameters.octaves = 4;
  noise_parameters.seed = 7;
  const PerlinNoise noise(noise_parameters);
  const PerturbedGround ground(model, &noise);
  const Check check = launch_all(ground, FastBounceParameters{});
  report("noise 0.3 m", check);
  EXPECT_LT(check.worst_penetration, 0.5 * amplitude);
  EXPECT_GT(check.flight_segments, 5000);
}

}  // namespace
}  // namespace talus

