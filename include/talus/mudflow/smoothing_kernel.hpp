// The smoothing kernel of the particles (paper 4.1, "smoothed particles" after Desbrun & Gascuel
// 1996): Wendland's C2 function in two dimensions (Wendland 1995), over the horizontal plane, of
// compact support R. It is positive definite, so particles do not pair up under pressure.
#pragma once

namespace talus {

// How many particle spacings the support radius spans: about 20 neighbours in the plane.
inline constexpr double kSupportPerSpacing = 2.4;

// W(r, R) = 7 / (pi R^2) (1 - q)^4 (1 + 4 q), q = r / R < 1, else 0 (1/m2); integrates to 1.
double kernel_value(double r, double support_radius);
// dW/dr (1/m3); zero at r = 0 and beyond R.
double kernel_slope(double r, double support_radius);

}  // namespace talus
