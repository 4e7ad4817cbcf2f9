// Perlin noise exactly as paper 3.4 builds it: a random table Tab[] filled once per
// simulation, a hash of the integer lattice coordinates E(lambda x), E(lambda y) into that
// table, bilinear interpolation of the four values A, B, C, D with frac(lambda x),
// frac(lambda y), and octaves Perlin = Perlin0(x) + 1/2 Perlin0(2x) + 1/4 Perlin0(4x) + ...
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

namespace talus {

struct PerlinParameters {
  double base_frequency = 1.0;   // lambda (1/m): of the order of 1 / rock size
  double amplitude = 0.1;        // m: the sum of octaves is scaled to stay within +-amplitude
  int octaves = 4;               // number of Perlin0 terms summed
  std::uint64_t seed = 0;        // fills Tab[] (counter-based, see core/counter_random)
  // Tab[] holds 2^table_bits values (1..20): lattice points share a value only by a hash
  // collision (probability 2^-table_bits), never periodically. Stochastic rock fall builds one
  // table per trajectory and uses a smaller one than the default.
  int table_bits = 12;
};

// Noise height and its gradient at one point, from one pass over the octaves.
struct NoiseSample {
  double value = 0;                                    // m
  Eigen::Vector2d gradient = Eigen::Vector2d::Zero();  // (d/dx, d/dy) of the value (-)
};

class PerlinNoise {
 public:
  explicit PerlinNoise(const PerlinParameters& parameters);

  // Noise height (m) at (x, y) in metres.
  double operator()(double x, double y) const;
  // Gradient (d/dx, d/dy) of the noise height, for the normals of the perturbed ground.
  Eigen::Vector2d gradient(double x, double y) const { return sample(x, y).gradient; }
  // Value and gradient together (equal to the two calls above).
  NoiseSample sample(double x, double y) const;
  const PerlinParameters& parameters() const { return parameters_; }

 private:
  struct Corners;  // A, B, C, D of one lattice square and the point's place in it
  Corners corners(double u, double v) const;
  PerlinParameters parameters_;
  std::vector<double> table_;    // uniform in [-1, 1]
  double octave_norm_;           // 1 / (1 + 1/2 + 1/4 + ...)
};

}  // namespace talus
