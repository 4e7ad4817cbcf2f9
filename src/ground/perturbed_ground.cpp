// The ground one stochastic trajectory sees (paper 3.4): the bilinear ground model of paper 2.2
// plus a Perlin perturbation of the elevation, scaled by the local lithology's noise amplitude,
// and the trajectory's random multipliers on the fast-mode material parameters.
#include "talus/ground/perturbed_ground.hpp"

#include <algorithm>
#include <cmath>

namespace talus {
namespace {

// Paper 3.4, "random variation of material parameters": the trajectory's multipliers, with the
// restitutions kept at most 1 so that no impact creates energy.
GroundMaterial varied(GroundMaterial material, const MaterialVariation& variation) {
  material.restitution_normal = std::min(1.0, material.restitution_normal * variation.restitution_normal);
  material.restitution_tangential = std::min(1.0, material.restitution_tangential * variation.restitution_tangential);
  material.friction *= variation.friction;
  return material;
}

Eigen::Vector3d upward_normal(const Eigen::Vector2d& gradient) {
  return Eigen::Vector3d(-gradient.x(), -gradient.y(), 1.0).normalized();
}

}  // namespace

PerturbedGround::PerturbedGround(const GroundModel& ground, const PerlinNoise* noise, MaterialVariation variation)
    : ground_(ground), noise_(noise), variation_(variation) {}

// Paper 3.4: z(x, y) + A(x, y) Perlin(x, y), with Perlin of unit amplitude and A the noise
// amplitude interpolated bilinearly from the nodes' lithology (paper 2.2).
double PerturbedGround::height(double x, double y) const {
  const NodeSquare square = ground_.locate(x, y);
  const double z = ground_.elevation(square);
  if (noise_ == nullptr) return z;
  const double amplitude = ground_.material_field(&GroundMaterial::noise_amplitude, square);
  return amplitude == 0.0 ? z : z + amplitude * (*noise_)(x, y);
}

// Normal of z + A Perlin from its gradient grad z + A grad Perlin. The term Perlin grad A,
// non-zero only where the lithology changes between nodes, is left out: it is at most
// |A1 - A2| / cell (a few hundredths), and keeping it would need the amplitude's own gradient.
Eigen::Vector3d PerturbedGround::normal(double x, double y) const {
  const NodeSquare square = ground_.locate(x, y);
  Eigen::Vector2d gradient = ground_.slope(square);
  if (noise_ != nullptr) {
    const double amplitude = ground_.material_field(&GroundMaterial::noise_amplitude, square);
    if (amplitude != 0.0) gradient += amplitude * noise_->gradient(x, y);
  }
  return upward_normal(gradient);
}

GroundMaterial PerturbedGround::material(double x, double y) const {
  return varied(ground_.material(x, y), variation_);
}

// height(), normal() and material() from one node-square look-up and one pass over the noise.
GroundPoint PerturbedGround::at(double x, double y) const {
  const NodeSquare square = ground_.locate(x, y);
  const GroundMaterial material = ground_.material(square);
  GroundPoint point;
  point.height = ground_.elevation(square);
  Eigen::Vector2d gradient = ground_.slope(square);
  if (noise_ != nullptr && material.noise_amplitude != 0.0) {
    const NoiseSample noise = noise_->sample(x, y);
    point.height += material.noise_amplitude * noise.value;
    gradient += material.noise_amplitude * noise.gradient;
  }
  point.normal = upward_normal(gradient);
  point.material = varied(material, variation_);
  return point;
}

}  // namespace talus
