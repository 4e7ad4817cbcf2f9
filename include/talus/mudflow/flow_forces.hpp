// The forces inside the mud and gravity (paper 4.1; docs/mudflow.md "Forces"), per unit mass of
// one column, in the ground's tangent plane:
// - pressure, from the gradient of the depth-integrated pressure in the symmetric SPH form, which
//   conserves momentum: a_i = - sum_j m_j (Pi_i / sigma_i^2 + Pi_j / sigma_j^2) grad_i W_ij with
//   Pi = rho0 g cos(theta) h^2 / (2 cos(theta)) = g cos^2(theta) sigma^2 / (2 rho0) (N/m), the
//   depth-integrated pressure per unit length of slope spread over the horizontal;
// - the paper's viscous internal friction, as the pairwise Morris et al. (1997) viscosity with
//   kinematic viscosity nu: a_i = sum_j m_j nu (sigma_i + sigma_j) / (sigma_i sigma_j)
//   (r_ij . grad_i W_ij) / (r_ij^2 + eps^2) (v_i - v_j), equal and opposite between pairs;
// - gravity (0, 0, -g).
// The sum is projected onto the tangent plane at the particle's foot: projecting a horizontal
// gradient onto the plane gives the surface gradient, so on a plane of slope theta the pressure
// term is -g cos(theta) dh/ds (Savage & Hutter 1989; Faccanoni & Mangeney 2012).
// With PressureColumn::vertical the pressure is instead the weight of the vertical column,
// Pi = g sigma^2 / (2 rho0), whose horizontal gradient is -g grad(h_vertical): the simplification
// of SamosAT and AvaFrame com1DFA's default SPH option (sphOption = 1), kept for code-to-code
// comparison; on a plane of slope theta it pushes 1 / cos^2(theta) times harder.
#pragma once

#include <cstddef>
#include <string>

#include <Eigen/Core>

#include "talus/mudflow/flow_density.hpp"
#include "talus/mudflow/particle_set.hpp"
#include "talus/mudflow/surface_following.hpp"

namespace talus {

// Which column's weight the depth-integrated pressure is (docs/mudflow.md section 4).
enum class PressureColumn {
  normal,    // thin-layer: rho0 g cos(theta) h^2 / 2 over the depth h normal to the ground
  vertical,  // rho0 g h_v^2 / 2 over the vertical column h_v = h / cos(theta) (com1DFA sphOption 1)
};

PressureColumn parse_pressure_column(const std::string& text);
const char* to_string(PressureColumn column);

struct FlowForceConstants {
  double mud_density = 2000;       // rho0 (kg/m3)
  double gravity = 9.81;           // m/s2
  double internal_viscosity = 0.5; // nu (m2/s)
  PressureColumn pressure = PressureColumn::normal;
  bool mean_velocity = false;      // measure the neighbours' mean velocity (for the lateral mixing)
};

// cos^2(theta) of the thin-layer pressure Pi / sigma^2 at a foot of slope cosine cos_slope, or 1
// for the vertical column's (-).
double pressure_slope_factor(PressureColumn column, double cos_slope);

// What one pass over a particle's neighbour list gives.
struct FlowAcceleration {
  Eigen::Vector3d acceleration;  // m/s2: pressure, internal friction and gravity, tangent to the ground
  double closing_speed = 0;      // m/s: the fastest approach_speed of a neighbour, at least 0 (time_levels.hpp)
  // m/s: with FlowForceConstants::mean_velocity, the SPH mean of the neighbours' velocities, i's
  // own left out, with the density's weights (sum_{j != i} m_j W_ij u_j / sum_{j != i} m_j W_ij;
  // i's own velocity where it has no neighbour); else zero.
  Eigen::Vector3d mean_velocity = Eigen::Vector3d::Zero();
};

// Pressure, internal friction and gravity on particle i, tangent to the ground at its foot, from
// its neighbour list (gather_density) and every particle's foot normal; the same pass measures how
// fast its neighbours close in, for its time step.
FlowAcceleration flow_acceleration(const ParticleSet& particles, std::size_t i, const NeighbourList& neighbours,
                                   const FootNormals& normals, const FlowForceConstants& constants);

}  // namespace talus
