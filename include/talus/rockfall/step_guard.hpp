// Blow-up detection for the full model's time steps (issue 4, Deliver 5; docs/architecture.md section 3:
// "numerical failure that could not be recovered"). An explicit step that is too long for the
// contact's stiffness multiplies the rock's energy at every step; the guard compares the energy
// before and after a step with what the step may add (nothing: gravity is in the potential
// energy and every other force dissipates), allowing for the integrator's bounded fluctuation.
// Equations: docs/rockfall-full.md, section 5.
#pragma once

#include <string>
#include <utility>

#include <Eigen/Core>

#include "talus/core/errors.hpp"
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

// A step that could not be made sound (docs/rockfall-full.md, section 5): its one-line message
// names the reason, the time, the centre and the shortest step tried; the fields keep them for
// the run's record of failed trajectories (run.json, "failures").
class StepFailure : public NumericalFailure {
 public:
  StepFailure(const std::string& message, double failed_time, const Eigen::Vector3d& failed_position, double failed_step,
              std::string failed_reason)
      : NumericalFailure(message),
        time(failed_time),
        position(failed_position),
        step(failed_step),
        reason(std::move(failed_reason)) {}
  double time;               // s since release
  Eigen::Vector3d position;  // m, the rock's centre
  double step;               // s, the shortest step tried
  std::string reason;        // e.g. "the step collapsed below its floor"
};

// Throws StepFailure with a one-line message naming the time (s), the centre (m) and the
// shortest step tried (s).
[[noreturn]] void throw_numerical_failure(double time, const Eigen::Vector3d& position, double step,
                                          const char* reason);

}  // namespace talus
