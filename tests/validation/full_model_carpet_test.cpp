// The piston carpet of paper 2.2 under the full model: pistons are lattice objects, independent
// of the window that holds them, so a carpet that scrolls with the rock (rows and columns added
// and dropped) gives the same trajectory as one that covers the whole path from the start
// (carpet_margin larger than the path), to 1e-9 m, as long as the rock never comes back over
// ground whose footprints were dropped.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "full_model_scenes.hpp"
#include "talus/ground/perlin_noise.hpp"
#include "talus/rockfall/full_model.hpp"

namespace talus {
namespace {

using testing_ground::Recorder;

TEST(FullModelCarpet, ScrollingCarpetGivesTheTrajectoryOfACarpetOverTheWholePath) {
  GroundMaterial soil = full_model_scenes::talus_soil();
  soil.noise_amplitude = 0.2;  // m: a rough slope, so that the rock bounces and turns
  const GroundModel model = full_model_scenes::inclined_plane(30, 20, 5.0, 100.0, 0.6, soil);
  PerlinParameters noise_parameters;
  noise_parameters.amplitude = 1.0;
  noise_parameters.octaves = 3;
  noise_parameters.seed = 11;
  const PerlinNoise noise(noise_parameters);
  const PerturbedGround ground(model, &noise);
  const Rock rock = full_model_scenes::block(BlockShape::ellipsoid, {1.2, 0.9, 0.8});
  RigidBodyState start = full_model_scenes::released(ground, 20.0, -50.0, 1.5);
  start.velocity = {2.0, 1.0, 0.0};
  start.angular_velocity = {1.0, -1.0, 0.5};

  FullModelParameters scrolling;
  scrolling.max_time = 2.0;
  FullModelParameters covering = scrolling;
  covering.carpet_margin = 15.0;  // m: more than the path
  Recorder scrolled, covered;
  FullModel(scrolling).run(ground, rock, start, scrolled);
  FullModel(covering).run(ground, rock, start, covered);

  const double path = (scrolled.final_sample.position - start.position).head<2>().norm();
  std::printf("carpet: path %.2f m, %zu samples\n", path, scrolled.samples.size());
  ASSERT_GT(path, 5.0);   // many carpet widths: the window really scrolled
  ASSERT_LT(path, 15.0);  // and the covering carpet held the whole path
  ASSERT_EQ(scrolled.samples.size(), covered.samples.size());
  double largest = 0.0;
  for (std::size_t k = 0; k < scrolled.samples.size(); ++k) {
    largest = std::max(largest, (scrolled.samples[k].position - covered.samples[k].position).norm());
    EXPECT_EQ(scrolled.samples[k].time, covered.samples[k].time);
  }
  std::printf("carpet: largest difference of the centre %.2e m\n", largest);
  EXPECT_LT(largest, 1e-9);  // issue 4: 1e-9 m
}

}  // namespace
}  // namespace talus
