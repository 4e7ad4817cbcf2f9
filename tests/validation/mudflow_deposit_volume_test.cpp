// Volume balance of a flow that entrains and deposits (issue 5: deposited volume equals released
// plus entrained volume within 2%), read from the layers: the release raster, erosion_depth and
// deposit_depth, each summed over the cells.
#include <gtest/gtest.h>

#include "mudflow_scenes.hpp"
#include "talus/mudflow/surface_following.hpp"

namespace talus {
namespace {

TEST(MudflowDepositVolume, DepositHoldsTheReleasedAndTheEntrainedMud) {
  const mudflow_scenes::Chute chute;
  const MudflowResult result = run_mudflow(chute.ground_model, chute.release_set, &chute.erodible,
                                           mudflow_scenes::Chute::settings(false, 1), nullptr);
  ASSERT_TRUE(result.layers.erosion_depth.has_value());
  ASSERT_EQ(result.outflow_volume, 0.0);
  const double released = mudflow_scenes::layer_volume(chute.release_set.depth);
  const double entrained = mudflow_scenes::layer_volume(*result.layers.erosion_depth);
  const double deposited = mudflow_scenes::layer_volume(result.layers.deposit_depth);
  // The bed matters: the flow entrains more than a tenth of its volume (measured 32%).
  EXPECT_GT(entrained, 0.1 * released);
  // 2% (issue 5). Measured: 7e-6 (float layers).
  EXPECT_NEAR(deposited, released + entrained, 0.02 * (released + entrained));
  // The engine's own counts agree with the layers (1e-4: the layers are float).
  EXPECT_NEAR(result.released_volume, released, 1e-4 * released);
  EXPECT_NEAR(result.entrained_volume, entrained, 1e-4 * released);
  // The engine counts the deposit in vertical columns; the layer holds depth normal to the
  // ground, so part of the deposit at the foot of the 30 degree slope reads cos(30) of its
  // column. Divided by the cos(theta) of each cell's centre (the slope's central differences,
  // cell_cos_slope), the layer gives the engine's volume to 1e-6 (float layers).
  const Grid<float>& deposit = result.layers.deposit_depth;
  const GridSpec& grid = deposit.spec();
  double vertical = 0;  // m3
  for (int row = 0; row < grid.height; ++row) {
    for (int col = 0; col < grid.width; ++col) {
      if (!deposit.is_valid(col, row)) continue;
      const double cos_theta = cell_cos_slope(chute.ground_model, col, row);
      vertical += deposit.at(col, row) / cos_theta * grid.cell_area();
    }
  }
  EXPECT_NEAR(result.deposited_volume, vertical, 1e-6 * released);
  EXPECT_NEAR(result.deposited_volume, deposited, 1e-3 * released);
}

}  // namespace
}  // namespace talus
