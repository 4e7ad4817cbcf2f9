// The ground one stochastic trajectory sees (paper 3.4): the bilinear ground model of paper 2.2
// plus a Perlin perturbation of the elevation, scaled by the local lithology's noise amplitude,
// and the trajectory's random multipliers on the fast-mode material parameters.
#include "talus/ground/perturbed_ground.hpp"

#include <algorithm>
#include <cmath>

namespace talus {
namespace {

// Paper 3.4, "random variation of material parameters": the trajectory's multipliers, with the
// restitutions kept at most 1 so that no impact creates energy; one friction multiplier scales
// the sliding and the rolling friction alike.
void vary(GroundMaterial& material, const MaterialVariation& variation) {
  material.restitution_normal = std::min(1.0, material.restitution_normal * variation.restitution_normal);
  material.restitution_tangential = std::min(1.0, material.restitution_tangential * variation.restitution_tangential);
  material.friction *= variation.friction;
  material.rolling_friction *= variation.friction;
}

Eigen::Vector3d upward_normal(const Eigen::Vector2d& gradient) {
  return Eigen::Vector3d(-gradient.x(), -gradient.y(), 1.0).normalized();
}

}  // namespace

PerturbedGround::PerturbedGround(const GroundModel& ground, const PerlinNoise* noise, MaterialVariation variation)
    : ground_(ground), noise_(noise), variation_(variation) {}

// Normal of z + A Perlin from its gradient grad z + A grad Perlin. The term Perlin grad A,
// non-zero only where the lithology changes between nodes, is left out: it is at most
// |A1 - A2| / cell (a few hundredths), and keeping it would need the amplitude's own gradient.
Eigen::Vector3d PerturbedGround::normal(double x, double y) const {
  const NodeSquare square = ground_.locate(x, y);
  Eigen::Vector2d gradient = ground_.slope(square);
  if (noise_ != nullptr) {
    const double amplitude = ground_.noise_amplitude(square);
    if (amplitude != 0.0) gradient += amplitude * noise_->gradient(x, y);
  }
  return upward_normal(gradient);
}

GroundMaterial PerturbedGround::material(double x, double y) const {
  GroundMaterial material = ground_.material(x, y);
  vary(material, variation_);
  return material;
}

// height(), normal() and material() from one node-square look-up and one pass over the noise.
GroundPoint PerturbedGround::at(double x, double y) const {
  const NodeSquare square = ground_.locate(x, y);
  GroundPoint point;
  point.material = ground_.material(square);
  point.height = ground_.elevation(square);
  Eigen::Vector2d gradient = ground_.slope(square);
  const double amplitude = point.material.noise_amplitude;
  if (noise_ != nullptr && amplitude != 0.0) {
    const NoiseSample noise = noise_->sample(x, y);
    point.height += amplitude * noise.value;
    gradient += amplitude * noise.gradient;
  }
  point.normal = upward_normal(gradient);
  vary(point.material, variation_);
  return point;
}

}  // namespace talus
