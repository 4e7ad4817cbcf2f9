// Tests of the basal resistance of each rheology and its implicit integration (docs/mudflow.md
// "Rheology").
#include "talus/mudflow/rheology.hpp"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "talus/core/errors.hpp"

namespace talus {
namespace {

constexpr double kRho = 2000.0;  // kg/m3
constexpr double kG = 9.81;      // m/s2

BasalContact contact(double depth, double normal_acceleration, double vegetation = 0.0) {
  BasalContact c;
  c.depth = depth;
  c.normal_acceleration = normal_acceleration;
  c.vegetation_deperdition = vegetation;
  return c;
}

TEST(Rheology, NamesRoundTripAndUnknownNamesAreRefused) {
  for (const Rheology r : {Rheology::viscous, Rheology::coulomb, Rheology::voellmy, Rheology::bingham}) {
    EXPECT_EQ(parse_rheology(to_string(r)), r);
  }
  try {
    parse_rheology("newtonian");
    FAIL() << "no InputError";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("newtonian"), std::string::npos);
  }
}

TEST(Rheology, EachLawGivesItsStressOverRhoH) {
  RheologyParameters p;
  p.friction = 0.3;
  p.turbulence = 400.0;
  p.viscosity = 50.0;
  p.yield_stress = 300.0;
  const BasalContact c = contact(2.0, 9.0, 0.01);
  const double rho_h = kRho * 2.0;  // kg/m2
  // Relative tolerance 1e-15: these are the closed forms, evaluated once more.
  p.rheology = Rheology::coulomb;
  BasalResistance r = basal_resistance(p, c, kRho, kG);
  EXPECT_DOUBLE_EQ(r.yield, 0.3 * 9.0);  // mu N / (rho h), N = rho h 9 m/s2
  EXPECT_EQ(r.linear, 0.0);
  EXPECT_DOUBLE_EQ(r.quadratic, 0.01);  // vegetation only
  p.rheology = Rheology::voellmy;
  r = basal_resistance(p, c, kRho, kG);
  EXPECT_DOUBLE_EQ(r.yield, 300.0 / rho_h + 0.3 * 9.0);  // (tau_y + mu N) / (rho h)
  EXPECT_DOUBLE_EQ(r.quadratic, kRho * kG / 400.0 / rho_h + 0.01);  // rho g u^2 / xi / (rho h)
  p.yield_stress = 0.0;  // Voellmy's own law
  r = basal_resistance(p, c, kRho, kG);
  EXPECT_DOUBLE_EQ(r.yield, 0.3 * 9.0);
  p.yield_stress = 300.0;
  p.rheology = Rheology::viscous;
  r = basal_resistance(p, c, kRho, kG);
  EXPECT_EQ(r.yield, 0.0);
  EXPECT_DOUBLE_EQ(r.linear, 3.0 * 50.0 / 2.0 / rho_h);  // 3 eta u / h / (rho h)
  p.rheology = Rheology::bingham;
  r = basal_resistance(p, c, kRho, kG);
  EXPECT_DOUBLE_EQ(r.yield, 300.0 / rho_h);  // tau_y / (rho h)
  EXPECT_DOUBLE_EQ(r.linear, 3.0 * 50.0 / 2.0 / rho_h);
}

TEST(Rheology, ResistanceStopsButNeverReverses) {
  BasalResistance r;
  r.yield = 3.0;  // m/s2
  // 1 m/s against 3 m/s2 for 1 s: stopped, not reversed; for 0.1 s: 0.7 m/s.
  EXPECT_EQ(resisted_speed(r, 1.0, 1.0), 0.0);
  EXPECT_NEAR(resisted_speed(r, 1.0, 0.1), 0.7, 1e-15);
  // Any step, however long, leaves a speed in [0, u0].
  r.linear = 50.0;
  r.quadratic = 20.0;
  for (const double step : {1e-6, 1e-3, 0.1, 10.0, 1e6}) {
    const double u = resisted_speed(r, 5.0, step);
    EXPECT_GE(u, 0.0);
    EXPECT_LE(u, 5.0);
  }
}

TEST(Rheology, ImplicitStepSolvesTheBackwardEulerEquation) {
  BasalResistance r;
  r.yield = 0.5;
  r.linear = 0.8;
  r.quadratic = 0.05;
  for (const double step : {0.01, 0.1, 1.0}) {
    const double u0 = 12.0, u1 = resisted_speed(r, u0, step);
    // u1 = u0 - dt (yield + linear u1 + quadratic u1^2), to rounding (1e-12 m/s).
    EXPECT_NEAR(u1, u0 - step * (r.yield + r.linear * u1 + r.quadratic * u1 * u1), 1e-12) << step;
  }
  // Without resistance the speed is unchanged.
  EXPECT_EQ(resisted_speed(BasalResistance{}, 3.5, 0.2), 3.5);
}

TEST(Rheology, VoellmyTerminalSpeedOnASlope) {
  // A column on a slope where gravity's pull g sin(theta) balances
  // tau_y / (rho h) + mu g cos(theta) + g u^2 / (xi h) reaches
  // u = sqrt(xi h (sin - mu cos - tau_y / (rho g h))): kick and resist with small steps until
  // steady. With tau_y = 0 it is Voellmy's own terminal speed.
  RheologyParameters p;
  p.rheology = Rheology::voellmy;
  const double theta = 0.5, h = 1.5, mu = 0.2;
  p.friction = mu;
  p.turbulence = 500.0;
  for (const double tau_y : {0.0, 1000.0}) {
    p.yield_stress = tau_y;
    const BasalResistance r = basal_resistance(p, contact(h, kG * std::cos(theta)), kRho, kG);
    double u = 0;
    for (int k = 0; k < 200000; ++k) u = resisted_speed(r, u + kG * std::sin(theta) * 1e-3, 1e-3);
    const double expected =
        std::sqrt(500.0 * h * (std::sin(theta) - mu * std::cos(theta) - tau_y / (kRho * kG * h)));
    EXPECT_NEAR(u, expected, 2e-3 * expected) << tau_y;  // 0.2%: first-order splitting error at dt = 1 ms
  }
}

TEST(Rheology, AYieldStressHoldsALayerThinnerThanItsStoppingDepth) {
  // Voellmy with a yield stress holds a layer at rest on a slope while
  // rho g h (sin - mu cos) <= tau_y, i.e. below h_stop = tau_y / (rho g (sin - mu cos)), and lets a
  // thicker one accelerate: the reason small releases stop and large ones run on.
  RheologyParameters p;
  p.rheology = Rheology::voellmy;
  p.friction = 0.1;
  p.turbulence = 500.0;
  p.yield_stress = 1000.0;
  const double theta = 20.0 * 3.14159265358979 / 180.0;
  const double stopping = p.yield_stress / (kRho * kG * (std::sin(theta) - p.friction * std::cos(theta)));
  for (const double factor : {0.9, 1.1}) {
    const BasalResistance r = basal_resistance(p, contact(factor * stopping, kG * std::cos(theta)), kRho, kG);
    double u = 0;
    for (int k = 0; k < 1000; ++k) u = resisted_speed(r, u + kG * std::sin(theta) * 1e-3, 1e-3);
    if (factor < 1.0) {
      EXPECT_EQ(u, 0.0) << "a layer of " << factor * stopping << " m";
    } else {
      EXPECT_GT(u, 0.1) << "a layer of " << factor * stopping << " m";
    }
  }
}

}  // namespace
}  // namespace talus
