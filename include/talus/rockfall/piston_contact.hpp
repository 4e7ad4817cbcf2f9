// The rock against the piston carpet (paper 3.3, steps 1-4; docs/architecture.md section 2). Step 1: each
// piston top, at its footprint, is tested against the rock's implicit function. Step 2: a top
// inside the rock is pushed down its axis to the rock's surface, found by bisection. Step 3:
// the piston responds by its stress cycle (stress_cycle.hpp) with the force that is minus the
// gradient of its energy with respect to the rock's motion, along the normal of the deformed
// ground; pistons the rock left go back to their footprint. Step 4: Coulomb friction at each
// contact point, regularised below a slip speed and solved linearly implicitly over a kick, and
// the vegetation's friction quadratic in speed (paper 2.1). Equations: docs/rockfall-full.md,
// section 3.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "talus/rockfall/piston_carpet.hpp"
#include "talus/rockfall/rigid_rock.hpp"

namespace talus {

// One loaded piston after pressing.
struct PistonTouch {
  std::int64_t i = 0, j = 0;                           // lattice indices
  Eigen::Vector3d arm = Eigen::Vector3d::Zero();       // contact point minus the rock's centre (m, world)
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();   // unit normal of the deformed ground, into the rock
  double load = 0;                                     // N: magnitude of the normal force
  double friction = 0;                                 // Coulomb mu (-)
  double rolling_friction = 0;                         // rolling mu_r (-)
  double vegetation_deperdition = 0;                   // c (1/m)
};

// An unloaded piston of the range, for the step-size rule of a coming contact.
struct NearPiston {
  Eigen::Vector3d arm = Eigen::Vector3d::Zero();    // its top (at the footprint) minus the rock's centre (m)
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  // its unit axis
  double gap = 0;                                   // m: the top lies at least this far outside the rock
};

// Normal response of the carpet at one rock position (paper 3.3, step 3).
struct NormalResponse {
  Eigen::Vector3d force = Eigen::Vector3d::Zero();    // N, world
  Eigen::Vector3d torque = Eigen::Vector3d::Zero();   // N m about the rock's centre, world
  double stiffness = 0;               // N/m: sum of k A / c^2 over loaded pistons (k the active slope)
  double rotational_stiffness = 0;    // N m/rad: sum of k A |arm x normal|^2 / c^2
  double elastic_energy = 0;          // J stored in the loaded pistons
  double dissipated = 0;              // J: increase of the pistons' loop energies in this press
  std::vector<PistonTouch> touches;   // loaded pistons, in lattice order
  std::vector<NearPiston> near;       // the range's other pistons
  Eigen::Vector3d centroid() const;   // m, world offset from the centre: load-weighted contact point
};

// A friction impulse on the rock (paper 3.3, step 4).
struct FrictionImpulse {
  Eigen::Vector3d linear = Eigen::Vector3d::Zero();   // N s
  Eigen::Vector3d angular = Eigen::Vector3d::Zero();  // N m s about the centre
};

// A piston's state before a press changed it, to undo a step.
struct PistonChange {
  std::int64_t i = 0, j = 0;
  PistonState before;
};

struct PistonContactParameters {
  double grazing_cosine = 0.2;           // floor of |g . axis| in the force's 1 / |g . axis| (-)
  double bisection_tolerance = 1e-9;     // m along the piston axis
  int bisection_iterations = 40;         // at most
  bool bound_every_compression = false;  // the recovery (docs/rockfall-full.md, section 5): the bound of
                                         // section 3.5 under every rock, not only under cut faces
};

// The pistons a press tests: the valid ones of a lattice window inside the carpet's, in lattice
// order (j, then i). Valid until the carpet's window changes.
struct PistonRange {
  CarpetWindow window;
  std::vector<Piston*> pistons;
  void gather(PistonCarpet& carpet, const CarpetWindow& range);
};

// Paper 3.3, steps 1-3, over the pistons of `range`: `previous` holds the pistons loaded at the
// last press; those outside the range go back to their footprint too. The rock's centre is at
// `centre` (m) and turned by `rotation` (body -> world). Every piston whose state changes is
// appended to `journal` with its old state. `response` is overwritten (its touches' storage is
// reused). Under a rock with cut faces on its surface (a fragment, RigidRock::has_cut_faces) a
// piston's compression is at most RigidRock::depth_inside at its rest top over grazing_cosine,
// which keeps it continuous at the cut faces' sharp edges (docs/rockfall-full.md, section 3.5);
// with bound_every_compression, under every rock.
void press_carpet(PistonCarpet& carpet, const PistonRange& range, const RigidRock& rock,
                  const Eigen::Vector3d& centre, const Eigen::Matrix3d& rotation,
                  const PistonContactParameters& parameters, const std::vector<PistonTouch>& previous,
                  NormalResponse& response, std::vector<PistonChange>& journal);

// The slope of the stress-cycle branch a piston is on (Pa/m): k1 while loading
// elastically, k2 while loading plastically, k3 below its largest compression.
double active_slope(const StressCycle& cycle, const PistonState& state);

// Paper 3.3, step 4, Coulomb friction over a kick of `duration` seconds, linearly implicit: per
// touch the force -c s on the slip s at its contact point (the contact point's velocity minus its
// part along the normal), c = mu N / max(slip_speed, |s*|) taken from the slip s* of the rock's
// velocity (m/s) and spin (rad/s, world) before the friction, and s the slip after the kick. So
// a slip faster than slip_speed meets mu N (regularised Coulomb) and a slower one a viscous stick
// of mu N / slip_speed, stable for any duration. mass (kg) and world_inertia (kg m2, about the
// centre, world axes) are the rock's.
// Rolling resistance (Azzoni et al. 1995, the rolling friction of STONE and Rockyfor3D), solved
// the same way: per touch a torque -c_r l^2 w_t against the spin's part across the normal w_t,
// l = |arm . normal| the centre's height above the contact plane, c_r = rolling mu N /
// max(slip_speed, l |w_t*|): a rolling rock meets a resisting torque rolling mu N l, which for a
// sphere gives the deceleration A g (rolling mu cos t - sin t), A = m r^2 / (I + m r^2), of
// docs/references.md, "Rock fall"; rolling_resistance scales the touch's rolling friction coefficient.
// Returns the impulse to add to the momenta. With `touch_forces`, also each touch's Coulomb
// friction force -c s (N, world, at its contact point; constant over the kick, so their sum is
// the linear impulse over `duration`), in the touches' order; rolling resistance is a torque
// only (the bond forces of fracture.hpp need the forces' points).
FrictionImpulse friction_impulse(const std::vector<PistonTouch>& touches, const Eigen::Vector3d& velocity,
                                 const Eigen::Vector3d& spin, double mass, const Eigen::Matrix3d& world_inertia,
                                 double slip_speed, double rolling_resistance, double duration,
                                 std::vector<Eigen::Vector3d>* touch_forces = nullptr);

// Paper 2.1 (vegetation) and 3.3, step 4: -c m (N / sum N) |v| v per touch for a rock of mass m
// (kg) moving at v (m/s), applied at the centre: the whole contact gives the fast mode's
// -c m |v| v (N).
Eigen::Vector3d vegetation_force(const std::vector<PistonTouch>& touches, const Eigen::Vector3d& velocity,
                                 double mass);

}  // namespace talus
