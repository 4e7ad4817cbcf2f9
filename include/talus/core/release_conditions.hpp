// The rock-fall conditions one release feature gives its own rocks (issue 16; docs/inputs.md,
// "Rock-fall attributes"): shape, size, density, start velocity and start height. Each empty
// field keeps the run's value (the CLI flag or scenario value).
#pragma once

#include <array>
#include <optional>

#include "talus/core/block_shape.hpp"

namespace talus {

struct ReleaseConditions {
  std::optional<BlockShape> shape;
  std::optional<std::array<double, 3>> axes;      // m, full lengths (a sphere: its diameter three times)
  std::optional<double> density;                  // kg/m3 (a `mass` attribute is turned into this)
  std::optional<std::array<double, 3>> velocity;  // m/s of the rock's centre: x east, y north, z up
  std::optional<double> release_height;           // m: the rock's lowest point above the ground at release

  bool empty() const { return !shape && !axes && !density && !velocity && !release_height; }
};

}  // namespace talus
