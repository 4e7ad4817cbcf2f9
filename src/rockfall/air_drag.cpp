// Air friction during flight (paper 3.2), integrated over a sphere (the force is inline in the
// header).
#include "talus/rockfall/air_drag.hpp"

namespace talus {

// Paper 3.2 divided by the mass: the coefficient of the drag deceleration -k |v| v.
double AirDrag::per_mass(double mass) const { return 0.5 * air_density * drag_coefficient * frontal_area / mass; }

}  // namespace talus
