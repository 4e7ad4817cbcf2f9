// The smoothed particles of a mud flow (paper 4.1, docs/architecture.md section 2 "Mud flow"), stored as a
// structure of arrays for speed. Talus follows the shallow-flow form of the paper's particles:
// each particle is a column of mud standing on the ground model. Its position is the column's
// foot on the bilinear surface (x, y in the DEM's CRS, z the ground elevation there), its
// velocity is tangent to the surface, and the SPH sum of its neighbours' masses over the
// horizontal plane is its areal density (kg/m2), from which depth and basal pressure follow
// (docs/mudflow.md, "State equation").
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace talus {

enum class ParticleState : std::uint8_t {
  flowing,    // integrated every step of its level
  deposited,  // stopped by basal resistance: frozen, still part of its neighbours' density
};

struct ParticleSet {
  std::vector<double> mass;             // kg
  std::vector<double> x, y, z;          // m: foot of the column on the ground surface
  std::vector<double> vx, vy, vz;       // m/s, tangent to the ground
  std::vector<double> ax, ay, az;       // m/s2: latest acceleration (time-step criteria)
  std::vector<double> density;          // kg/m2: areal density from the SPH sum (horizontal)
  std::vector<double> depth;            // m: flow thickness normal to the ground
  std::vector<double> pressure;         // Pa: basal pressure of the column
  std::vector<double> radius;           // m: support radius of the smoothing kernel
  std::vector<double> still_time;       // s: how long the particle has been slower than the stop speed
  std::vector<std::uint8_t> level;      // time-step level: step = longest step / 2^level
  std::vector<ParticleState> state;

  std::size_t size() const { return mass.size(); }
  // Appends a flowing particle at level 0 with zero acceleration, density, depth and pressure;
  // returns its index.
  std::size_t add(double particle_mass, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                  double support_radius);
  // Keeps the particles whose `keep` flag is set, in their order.
  void keep_only(const std::vector<char>& keep);
  // Puts the particles in the order given (order[k] = old index of the new k-th particle).
  void reorder(const std::vector<std::uint32_t>& order);

  Eigen::Vector3d position(std::size_t i) const { return {x[i], y[i], z[i]}; }
  Eigen::Vector3d velocity(std::size_t i) const { return {vx[i], vy[i], vz[i]}; }

  // Sums in index order (the same result whatever the thread count).
  double total_mass() const;                  // kg
  Eigen::Vector3d total_momentum() const;     // kg m/s
  double kinetic_energy() const;              // J
};

}  // namespace talus
