// The paper's full rock-ground model (paper 2.1, 2.2, 3.1-3.3; docs/architecture.md section 2): a rigid rock
// (implicit surface, mass and inertia from its shape and density, orientation as a quaternion)
// on the elasto-plastic piston carpet under its bounding box. Contacts: pistons whose top is
// inside the rock are pushed back along their axis to its surface (bisection on the implicit
// function), respond by their stress cycle along the normal of the deformed surface, with
// Coulomb friction from the lithology and vegetation friction quadratic in speed; torques from
// the contact points; air drag as the surface integral of paper 3.2. Time steps follow the
// contact stiffness and the rock's mass; a guard retries blown-up steps with smaller ones and
// throws NumericalFailure when it cannot recover. A block may be pre-fractured into parts held by
// breakable bonds (paper fig. 4, fracture.hpp); its fragments continue as rocks of their own.
// Equations, choices and parameters: docs/rockfall-full.md.
#pragma once

#include "talus/rockfall/trajectory_model.hpp"

namespace talus {

struct FullModelParameters {
  double gravity = 9.81;              // m/s2
  double air_density = 1.225;         // kg/m3
  double drag_coefficient = 0.1;      // Cx (-), paper 3.2; 0 disables drag
  double max_time = 300.0;            // s of simulated time
  double stop_speed = 0.1;            // m/s: a rock whose centre and rim moved on average slower than
  double stop_duration = 0.5;         // this over a window of this many s, in contact at its end, is at rest
  double carpet_spacing = 0.125;      // piston spacing as a fraction of the rock's diameter (-)
  double time_step_factor = 0.05;     // contact step = factor x 2 pi sqrt(m / K), K the stiffest
                                      // contact stiffness of the pistons under the rock (-)
  double max_flight_step = 0.02;      // s: longest step in flight (near the ground, also the approach
                                      // rule below)
  double sample_spacing = 2.5;        // m: longest path between two reported samples
  double friction_slip_speed = 0.01;  // m/s: Coulomb friction is regularised below this slip speed
  double rolling_resistance = 1.0;    // multiplier of the lithology's rolling friction (-): 1 = the
                                      // table's rolling friction, as in fast mode; 0 = pure rolling
  bool guard = true;                  // detect blow-up and retry with smaller steps
  int max_retries = 8;                // halvings of a step before it counts as failed
  int restarts = 2;                   // a failed step (collapse, blow-up, stall) restarts the rock from its last
                                      // sound state, at least kCheckpointSteps back, with contact steps a quarter
                                      // as long; this many times per rock before NumericalFailure
                                      // (docs/rockfall-full.md, section 5, "Recovery")
  // Added by the implementation (docs/rockfall-full.md, section 8):
  double approach_fraction = 0.25;    // per step, the rock's material at a piston top closes on it (or
                                      // leaves it) by at most this fraction of the spacing beyond its gap (-)
  int fresh_contact_pistons = 4;      // a coming contact's stiffness is k3 x this many pistons' area (-)
  double grazing_cosine = 0.2;        // floor of |normal . piston axis| in the piston force (-)
  double guard_tolerance = 0.05;      // a step may raise kinetic + potential + elastic energy by this
                                      // fraction of (kinetic + elastic + m g spacing) before it counts as
                                      // blown up (-)
  double carpet_margin = 0.0;         // m added around the carpet's region (tests: larger than the path,
                                      // the carpet covers it all)
  int surface_samples = 256;          // samples of the rock's implicit surface (air drag)
  int mass_resolution = 32;           // cells per axis of the mass and inertia integration (0.4% at 32)
  // Pre-fractured blocks (paper 3.1, fig. 4; fracture.hpp, docs/rockfall-full.md, section 11):
  int fracture_parts = 1;             // 1: intact; 2: halves across the longest axis; 4: also across the
                                      // second; 8: octants
  double fracture_strength = 1.0e6;   // N: a bond between two parts breaks when its force exceeds this
};

// Energy bookkeeping of one run (J), exact sums over steps (issue 4, Deliver 7). For a rock that
// broke, the sums over its fragments: their final kinetic, potential and elastic energies, and
// every loss of the block and of each fragment.
struct EnergyBalance {
  double kinetic = 0;          // translation + rotation, now
  double potential = 0;        // m g z of the centre, now
  double elastic = 0;          // stored in pistons under the rock, now
  double deformation_loss = 0; // dissipated by the stress cycles (loop areas), so far
  double friction_loss = 0;    // Coulomb and vegetation, so far
  double drag_loss = 0;        // air friction, so far
  double total() const { return kinetic + potential + elastic + deformation_loss + friction_loss + drag_loss; }
};

class FullModel final : public TrajectoryModel {
 public:
  explicit FullModel(FullModelParameters parameters = {}) : parameters_(parameters) {}
  // Returns the stop reason of the trajectory's first fragment (the whole rock when it does not
  // break; trajectory_observer.hpp).
  StopReason run(const PerturbedGround& ground, const Rock& rock, RigidBodyState start,
                 TrajectoryObserver& observer) const override;
  // As run(), and fills `balance` with the final energy bookkeeping (for tests and calibration).
  StopReason run(const PerturbedGround& ground, const Rock& rock, RigidBodyState start, TrajectoryObserver& observer,
                 EnergyBalance& balance) const;
  const FullModelParameters& parameters() const { return parameters_; }

 private:
  FullModelParameters parameters_;
};

}  // namespace talus
