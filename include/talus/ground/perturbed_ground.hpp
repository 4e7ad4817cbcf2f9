// The ground one stochastic trajectory sees (paper 3.4): the bilinear ground model plus a
// Perlin perturbation of the elevation scaled by the local lithology's noise amplitude, and
// the trajectory's random variation of the material parameters.
#pragma once

#include <Eigen/Core>

#include "talus/ground/ground_model.hpp"
#include "talus/ground/perlin_noise.hpp"

namespace talus {

// Everything the ground says at one point, from one shared evaluation.
struct GroundPoint {
  double height = 0;                                     // m, as height()
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();     // as normal()
  GroundMaterial material;                               // as material()
};

// Multipliers drawn once per trajectory (1 = the table's value).
struct MaterialVariation {
  double restitution_normal = 1.0;
  double restitution_tangential = 1.0;
  double friction = 1.0;
};

class PerturbedGround {
 public:
  // noise: unit-amplitude Perlin noise, or nullptr for the unperturbed ground. Both must
  // outlive this object.
  PerturbedGround(const GroundModel& ground, const PerlinNoise* noise, MaterialVariation variation = {});

  bool contains(double x, double y) const { return ground_.contains(x, y); }
  // Paper 3.4: z(x, y) + A(x, y) * noise(x, y) (m), with noise of unit amplitude and A the noise
  // amplitude interpolated bilinearly from the nodes' lithology (paper 2.2). Inline: the
  // trajectory models ask for it about a thousand times per trajectory.
  double height(double x, double y) const {
    const NodeSquare square = ground_.locate(x, y);
    const double z = ground_.elevation(square);
    if (noise_ == nullptr) return z;
    const double amplitude = ground_.noise_amplitude(square);
    return amplitude == 0.0 ? z : z + amplitude * (*noise_)(x, y);
  }
  // Unit upward normal of the perturbed surface.
  Eigen::Vector3d normal(double x, double y) const;
  // Interpolated material with the trajectory's variation applied (restitutions capped at 1).
  GroundMaterial material(double x, double y) const;
  // height, normal and material at once, sharing the interpolation work (equal to the three).
  GroundPoint at(double x, double y) const;
  const GroundModel& model() const { return ground_; }

 private:
  const GroundModel& ground_;
  const PerlinNoise* noise_;
  MaterialVariation variation_;
};

}  // namespace talus
