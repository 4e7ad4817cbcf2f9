// Wendland C2 kernel in two dimensions (Wendland 1995), support radius R.
#include "talus/mudflow/smoothing_kernel.hpp"

#include <numbers>

namespace talus {

// W = 7 / (pi R^2) (1 - q)^4 (1 + 4 q) for q = r / R < 1 (1/m2).
double kernel_value(double r, double support_radius) {
  const double q = r / support_radius;
  if (q >= 1) return 0;
  const double u = 1 - q;
  const double u2 = u * u;
  return 7.0 / (std::numbers::pi * support_radius * support_radius) * u2 * u2 * (1 + 4 * q);
}

// dW/dr = 7 / (pi R^3) (-20 q (1 - q)^3) (1/m3).
double kernel_slope(double r, double support_radius) {
  const double q = r / support_radius;
  if (q >= 1) return 0;
  const double u = 1 - q;
  return -140.0 / (std::numbers::pi * support_radius * support_radius * support_radius) * q * u * u * u;
}

}  // namespace talus
