// Basal resistance of the mud for each rheology (docs/mudflow.md "Rheology"), and its implicit
// integration over one step.
#include "talus/mudflow/rheology.hpp"

#include <algorithm>
#include <cmath>

#include "talus/core/errors.hpp"

namespace talus {

Rheology parse_rheology(const std::string& text) {
  if (text == "viscous") return Rheology::viscous;
  if (text == "coulomb") return Rheology::coulomb;
  if (text == "voellmy") return Rheology::voellmy;
  if (text == "bingham") return Rheology::bingham;
  throw InputError("unknown rheology '" + text + "': expected viscous, coulomb, voellmy or bingham");
}

const char* to_string(Rheology rheology) {
  switch (rheology) {
    case Rheology::viscous:
      return "viscous";
    case Rheology::coulomb:
      return "coulomb";
    case Rheology::voellmy:
      return "voellmy";
    case Rheology::bingham:
      return "bingham";
  }
  return "unknown";
}

// Shear stresses (Pa) divided by the column's mass per area rho0 h (kg/m2):
//   coulomb  tau = mu N                     -> mu (g cos(theta) + u^2 kappa)
//   voellmy  tau = tau_y + mu N + rho0 g u^2 / xi
//                                           -> tau_y / (rho0 h) + the same plus g u^2 / (xi h)
//   viscous  tau = 3 eta u / h              -> 3 eta u / (rho0 h^2)   (laminar Newtonian layer)
//   bingham  tau = tau_y + 3 eta u / h      -> tau_y / (rho0 h) + 3 eta u / (rho0 h^2)
// and the vegetation's c |u| u for every rheology (as for rocks, docs/architecture.md section 2).
BasalResistance basal_resistance(const RheologyParameters& parameters, const BasalContact& contact,
                                 double mud_density, double gravity) {
  const double h = contact.depth;
  const double mu = parameters.friction;
  BasalResistance resistance;
  switch (parameters.rheology) {
    case Rheology::coulomb:
      resistance.yield = mu * contact.normal_acceleration;
      break;
    case Rheology::voellmy:
      resistance.yield = parameters.yield_stress / (mud_density * h) + mu * contact.normal_acceleration;
      resistance.quadratic = gravity / (parameters.turbulence * h);
      break;
    case Rheology::viscous:
      resistance.linear = 3.0 * parameters.viscosity / (mud_density * h * h);
      break;
    case Rheology::bingham:
      resistance.yield = parameters.yield_stress / (mud_density * h);
      resistance.linear = 3.0 * parameters.viscosity / (mud_density * h * h);
      break;
  }
  resistance.quadratic += contact.vegetation_deperdition;
  return resistance;
}

// Backward Euler on du/dt = -(yield + linear u + quadratic u^2) for u > 0: the positive root of
// quadratic dt u1^2 + (1 + linear dt) u1 - (u0 - yield dt) = 0, written in the form that stays
// accurate when the quadratic term is small (no cancellation).
double resisted_speed(const BasalResistance& resistance, double speed, double duration) {
  const double driven = speed - resistance.yield * duration;
  if (!(driven > 0.0)) return 0.0;
  const double a = resistance.quadratic * duration;
  const double b = 1.0 + resistance.linear * duration;
  const double root = 2.0 * driven / (b + std::sqrt(b * b + 4.0 * a * driven));
  return std::clamp(root, 0.0, speed);
}

}  // namespace talus
