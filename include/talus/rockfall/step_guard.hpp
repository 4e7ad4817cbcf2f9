// Blow-up detection for the full model's time steps (issue 4, Deliver 5; docs/architecture.md section 3:
// "numerical failure that could not be recovered"). An explicit step that is too long for the
// contact's stiffness multiplies the rock's energy at every step; the guard compares the energy
// before and after a step with what the step may add (nothing: gravity is in the potential
// energy and every other force dissipates), allowing for the integrator's bounded fluctuation.
// Equations: docs/rockfall-full.md, section 5.
#pragma once

#include <Eigen/Core>

#include "talus/rockfall/rigid_rock.hpp"

namespace talus {

// Energies of the rock and the pistons under it at one instant (J).
struct StepEnergy {
  double kinetic = 0;     // translation + rotation
  double potential = 0;   // m g z of the centre
  double elastic = 0;     // stored in the loaded pistons
  double mechanical() const { return kinetic + potential + elastic; }
};

// True when the step ended in a finite state whose mechanical energy exceeds the one before by
// at most tolerance x (kinetic + elastic before + floor) (J): the fluctuation of a stable
// kick-drift-kick step is a fraction of the energy that oscillates in the contact.
bool step_is_sound(const RockState& after, const StepEnergy& before, const StepEnergy& after_energy,
                   double tolerance, double floor);

// Throws NumericalFailure with a one-line message naming the time (s), the centre (m) and the
// shortest step tried (s).
[[noreturn]] void throw_numerical_failure(double time, const Eigen::Vector3d& position, double step,
                                          const char* reason);

}  // namespace talus
