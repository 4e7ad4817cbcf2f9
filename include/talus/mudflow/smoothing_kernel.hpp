// The smoothing kernel of the particles (paper 4.1, "smoothed particles" after Desbrun & Gascuel
// 1996): Wendland's C2 function in two dimensions (Wendland 1995), over the horizontal plane, of
// compact support R. It is positive definite, so particles do not pair up under pressure.
#pragma once

#include <algorithm>
#include <numbers>

namespace talus {

// How many particle spacings the support radius spans: about 20 neighbours in the plane.
inline constexpr double kSupportPerSpacing = 2.4;

// W(r, R) = 7 / (pi R^2) (1 - q)^4 (1 + 4 q), q = r / R < 1, else 0 (1/m2); integrates to 1.
double kernel_value(double r, double support_radius);
// dW/dr (1/m3); zero at r = 0 and beyond R.
double kernel_slope(double r, double support_radius);

// W and dW/dr together, from the inverse support radius 1/R (1/m), inline: the innermost loops
// of the simulation use it, where kernel_value and kernel_slope would cost a call and a division
// each (tests/unit/mudflow/smoothing_kernel_test.cpp checks that they agree).
struct KernelSample {
  double value;  // W(r, R) (1/m2)
  double slope;  // dW/dr (1/m3)
};
inline KernelSample sample_kernel(double r, double inverse_support_radius) {
  const double inverse = inverse_support_radius;
  const double q = r * inverse;
  // Beyond the support both are zero: a maximum rather than `q < 1 ? 1 - q : 0`, because a
  // conditional subtraction keeps a loop from being vectorised (flow_density.cpp).
  const double u = std::max(1.0 - q, 0.0);
  const double u3 = u * u * u;
  const double scale = 7.0 / std::numbers::pi * inverse * inverse;  // 1/m2
  return {scale * u3 * u * (1.0 + 4.0 * q), -20.0 * scale * inverse * q * u3};
}

}  // namespace talus
