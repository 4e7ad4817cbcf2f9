// Tests of the stop reasons' names (written into trajectories.gpkg and run.json).
#include "talus/rockfall/trajectory_observer.hpp"

#include <string>

#include <gtest/gtest.h>

namespace talus {
namespace {

TEST(StopReason, NamesAreStable) {
  EXPECT_EQ(std::string(to_string(StopReason::at_rest)), "at_rest");
  EXPECT_EQ(std::string(to_string(StopReason::max_time)), "max_time");
  EXPECT_EQ(std::string(to_string(StopReason::left_dem)), "left_dem");
  EXPECT_EQ(std::string(to_string(StopReason::nodata_area)), "nodata_area");
}

}  // namespace
}  // namespace talus
