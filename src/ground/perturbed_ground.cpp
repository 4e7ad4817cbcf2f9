// The ground one stochastic trajectory sees (paper 3.4): the bilinear ground model of paper 2.2
// plus a Perlin perturbation of the elevation, scaled by the local lithology's noise amplitude,
// and the trajectory's random multipliers on the fast-mode material parameters.
#include "talus/ground/perturbed_ground.hpp"

#include <algorithm>
#include <cmath>

namespace talus {
namespace {

// Lower node index of the square holding the continuous node coordinate u, and the place in it:
// the same squares as the ground model's interpolation (floor(u) kept within [0, count - 2]).
int lower_node(double u, int count) {
  const double last_square = static_cast<double>(count > 1 ? count - 2 : 0);
  double base = std::floor(u);
  if (!(base >= 0.0)) base = 0.0;
  if (base > last_square) base = last_square;
  return static_cast<int>(base);
}

// The lithology's noise amplitude A at (x, y), interpolated bilinearly from the nodes exactly as
// GroundModel::material interpolates it (paper 2.2), without blending the other eight fields.
double noise_amplitude(const GroundModel& ground, double x, double y) {
  const GridSpec& spec = ground.spec();
  const Grid<GroundMaterial>& nodes = ground.material_grid();
  const double col = spec.col_of(x);
  const double row = spec.row_of(y);
  const int col0 = lower_node(col, spec.width);
  const int row0 = lower_node(row, spec.height);
  const int col1 = spec.width > 1 ? col0 + 1 : col0;
  const int row1 = spec.height > 1 ? row0 + 1 : row0;
  const double fx = col - col0;
  const double fy = row - row0;
  return (1.0 - fy) * ((1.0 - fx) * nodes.at(col0, row0).noise_amplitude + fx * nodes.at(col1, row0).noise_amplitude) +
         fy * ((1.0 - fx) * nodes.at(col0, row1).noise_amplitude + fx * nodes.at(col1, row1).noise_amplitude);
}

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
  const double z = ground_.elevation(x, y);
  if (noise_ == nullptr) return z;
  const double amplitude = noise_amplitude(ground_, x, y);
  return amplitude == 0.0 ? z : z + amplitude * (*noise_)(x, y);
}

// Normal of z + A Perlin from its gradient grad z + A grad Perlin. The term Perlin grad A,
// non-zero only where the lithology changes between nodes, is left out: it is at most
// |A1 - A2| / cell (a few hundredths), and keeping it would need the amplitude's own gradient.
Eigen::Vector3d PerturbedGround::normal(double x, double y) const {
  Eigen::Vector2d gradient = ground_.slope(x, y);
  if (noise_ != nullptr) {
    const double amplitude = noise_amplitude(ground_, x, y);
    if (amplitude != 0.0) gradient += amplitude * noise_->gradient(x, y);
  }
  return upward_normal(gradient);
}

GroundMaterial PerturbedGround::material(double x, double y) const {
  return varied(ground_.material(x, y), variation_);
}

// height(), normal() and material() with one material interpolation for all three.
GroundPoint PerturbedGround::at(double x, double y) const {
  const GroundMaterial material = ground_.material(x, y);
  GroundPoint point;
  point.height = ground_.elevation(x, y);
  Eigen::Vector2d gradient = ground_.slope(x, y);
  if (noise_ != nullptr && material.noise_amplitude != 0.0) {
    point.height += material.noise_amplitude * (*noise_)(x, y);
    gradient += material.noise_amplitude * noise_->gradient(x, y);
  }
  point.normal = upward_normal(gradient);
  point.material = varied(material, variation_);
  return point;
}

}  // namespace talus
