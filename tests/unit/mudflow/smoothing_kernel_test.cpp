// Tests of the 2D Wendland C2 smoothing kernel (paper 4.1, Wendland 1995).
#include "talus/mudflow/smoothing_kernel.hpp"

#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

namespace talus {
namespace {

// Integral of W over the plane, 2 pi int_0^R W(r) r dr, by Simpson's rule on n intervals.
double plane_integral(double support_radius, int n) {
  const double h = support_radius / n;
  double sum = 0;
  for (int k = 0; k <= n; ++k) {
    const double r = k * h;
    const double weight = (k == 0 || k == n) ? 1.0 : (k % 2 == 1 ? 4.0 : 2.0);
    sum += weight * kernel_value(r, support_radius) * r;
  }
  return 2.0 * std::numbers::pi * sum * h / 3.0;
}

TEST(SmoothingKernel, IntegratesToOneOverThePlane) {
  // Tolerance 1e-6 (issue 5): Simpson's error on 2000 intervals of this polynomial is ~1e-13.
  for (const double radius : {0.3, 1.0, 2.4, 24.0}) EXPECT_NEAR(plane_integral(radius, 2000), 1.0, 1e-6) << radius;
}

TEST(SmoothingKernel, SlopeIsTheDerivativeOfTheValue) {
  // Central difference with step 1e-6 R: truncation and rounding error below 1e-6 relative to
  // the largest slope |dW/dr| ~ 1.7 / R^3.
  const double radius = 2.4;
  const double scale = 7.0 / (std::numbers::pi * radius * radius * radius);
  for (double q = 0.01; q < 0.995; q += 0.0137) {
    const double r = q * radius, step = 1e-6 * radius;
    const double numeric = (kernel_value(r + step, radius) - kernel_value(r - step, radius)) / (2.0 * step);
    EXPECT_NEAR(kernel_slope(r, radius), numeric, 1e-6 * scale) << q;
  }
}

TEST(SmoothingKernel, CompactSupportAndPeakAtTheCentre) {
  const double radius = 1.5;
  EXPECT_DOUBLE_EQ(kernel_value(0.0, radius), 7.0 / (std::numbers::pi * radius * radius));
  EXPECT_EQ(kernel_slope(0.0, radius), 0.0);
  EXPECT_EQ(kernel_value(radius, radius), 0.0);
  EXPECT_EQ(kernel_value(2.0 * radius, radius), 0.0);
  EXPECT_EQ(kernel_slope(radius, radius), 0.0);
  // Decreasing on (0, R): the slope is negative there.
  for (double q = 0.05; q < 1.0; q += 0.05) EXPECT_LT(kernel_slope(q * radius, radius), 0.0) << q;
}

TEST(SmoothingKernel, InlineSampleAgreesWithValueAndSlope) {
  // 1e-13 relative: the same polynomial, evaluated from 1/R instead of R.
  for (const double radius : {0.3, 2.4, 24.0}) {
    for (double q = 0.0; q < 1.2; q += 0.031) {
      const KernelSample sample = sample_kernel(q * radius, 1.0 / radius);
      const double value = kernel_value(q * radius, radius), slope = kernel_slope(q * radius, radius);
      EXPECT_NEAR(sample.value, value, 1e-13 * std::abs(value)) << radius << " " << q;
      EXPECT_NEAR(sample.slope, slope, 1e-13 * std::abs(slope)) << radius << " " << q;
    }
  }
}

}  // namespace
}  // namespace talus
