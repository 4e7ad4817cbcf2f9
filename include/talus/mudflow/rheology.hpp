// Basal and internal resistance of the mud (paper 4.1 "viscous internal friction", docs/architecture.md
// section 2 "contact and basal friction against the ground model"). Equations, units and the
// ranges users meet: docs/mudflow.md, "Rheology".
#pragma once

#include <string>

namespace talus {

enum class Rheology {
  viscous,   // the paper's viscous substance: laminar basal shear 3 eta u / h
  coulomb,   // basal shear mu N
  voellmy,   // tau_y + mu N + rho g u^2 / xi (tau_y 0: Voellmy's own law)
  bingham,   // yield stress tau_y plus laminar viscous shear
};

// "viscous", "coulomb", "voellmy", "bingham"; throws InputError naming the text otherwise.
Rheology parse_rheology(const std::string& text);
const char* to_string(Rheology rheology);

struct RheologyParameters {
  Rheology rheology = Rheology::voellmy;
  // Defaults: the debris-flow material (src/cli/mudflow_materials.toml, docs/mudflow.md "Materials").
  double friction = 0.1;           // Coulomb friction coefficient mu of coulomb and Voellmy (-)
  double turbulence = 500;         // xi of Voellmy (m/s2)
  double viscosity = 100;          // dynamic viscosity eta (Pa s): viscous and Bingham
  double yield_stress = 1000;      // tau_y of Voellmy and Bingham (Pa); 0: Voellmy's own law
  double internal_viscosity = 0.5; // kinematic viscosity of the SPH internal friction (m2/s)
  // C of the lateral mixing (-): each column's velocity relaxes towards its neighbours' mean
  // by a drag (C / s) |u - u_mean| (u - u_mean), s = sqrt(m / sigma) its footprint's side (AvaFrame
  // com1DFA's artificial viscosity, subgridMixingFactor = 100); 0: none.
  double lateral_mixing = 0;
};

// The basal shear stress of one column divided by its mass per area (rho0 h), written as a
// deceleration opposite the velocity that grows with the speed u:
//   deceleration = yield + linear u + quadratic u^2   (m/s2).
struct BasalResistance {
  double yield = 0;       // m/s2: Coulomb mu N / (rho0 h), Bingham tau_y / (rho0 h), Voellmy both
  double linear = 0;      // 1/s: laminar 3 eta / (rho0 h^2)
  double quadratic = 0;   // 1/m: Voellmy g / (xi h) plus vegetation c
};

// What the ground and the column give the rheology at one particle.
struct BasalContact {
  double depth = 0;                   // m: flow thickness normal to the ground (> 0)
  double normal_acceleration = 0;     // m/s2: g cos(theta) + u^2 kappa, the normal stress / (rho0 h), >= 0
  double vegetation_deperdition = 0;  // 1/m: the vegetation's c in c |u| u
};

// Basal resistance of the chosen rheology (docs/mudflow.md "Rheology"; docs/architecture.md section 2):
// coulomb mu N, voellmy tau_y + mu N + rho0 g u^2 / xi, viscous 3 eta u / h, bingham tau_y + 3 eta u / h,
// each plus the vegetation's c |u| u; mud_density rho0 (kg/m3), gravity g (m/s2).
BasalResistance basal_resistance(const RheologyParameters& parameters, const BasalContact& contact,
                                 double mud_density, double gravity);

// The speed (m/s) after `duration` (s) of resistance, solved implicitly:
// u1 = u0 - duration (yield + linear u1 + quadratic u1^2), and 0 when the yield part alone
// stops the particle within the step. The result lies in [0, speed]: resistance can stop a
// particle but never reverse it, whatever the step.
double resisted_speed(const BasalResistance& resistance, double speed, double duration);

}  // namespace talus
