// Perlin noise of paper 3.4: Tab[] filled once from the seed, Hash(E(lambda x), E(lambda y))
// into it, bilinear interpolation of A, B, C, D, and octaves weighted 1, 1/2, 1/4, ...
#include "talus/ground/perlin_noise.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "talus/core/counter_random.hpp"

namespace talus {
namespace {

// The counter-random stream (source, run) that fills Tab[] for a given seed.
constexpr std::uint64_t kTableSource = 0x5045524C494E3334ULL;  // "PERLIN34"
constexpr std::uint64_t kTableRun = 0;

// Hash(i, j): an odd-multiplier combination of the two lattice coordinates (two's complement,
// so negative coordinates are fine), then the xor-shift-multiply finaliser of MurmurHash3
// (Appleby), whose top table_bits bits index Tab[].
std::size_t lattice_hash(std::int64_t i, std::int64_t j, int table_bits) {
  std::uint64_t h =
      static_cast<std::uint64_t>(i) * 0x9E3779B97F4A7C15ULL + static_cast<std::uint64_t>(j) * 0xD1B54A32D192ED03ULL;
  h ^= h >> 33;
  h *= 0xFF51AFD7ED558CCDULL;
  h ^= h >> 33;
  h *= 0xC4CEB9FE1A85EC53ULL;
  h ^= h >> 33;
  return static_cast<std::size_t>(h >> (64 - table_bits));
}

// One Perlin0 lattice square at scaled coordinates (u, v) = (lambda x, lambda y): its corner
// E(u), E(v) and the fractional parts frac(u), frac(v).
struct LatticeCell {
  std::int64_t i, j;
  double fu, fv;
};

LatticeCell lattice_cell(double u, double v) {
  const double floor_u = std::floor(u);
  const double floor_v = std::floor(v);
  return {static_cast<std::int64_t>(floor_u), static_cast<std::int64_t>(floor_v), u - floor_u, v - floor_v};
}

}  // namespace

PerlinNoise::PerlinNoise(const PerlinParameters& parameters)
    : parameters_(parameters), table_(std::size_t{1} << std::clamp(parameters.table_bits, 1, 20)) {
  parameters_.table_bits = std::clamp(parameters.table_bits, 1, 20);
  CounterRandom random(parameters_.seed, kTableSource, kTableRun);
  for (double& value : table_) value = random.uniform(-1.0, 1.0);
  double weight_sum = 0.0;
  for (int k = 0; k < parameters_.octaves; ++k) weight_sum += std::ldexp(1.0, -k);
  octave_norm_ = weight_sum > 0.0 ? 1.0 / weight_sum : 0.0;
}

double PerlinNoise::table_at(std::int64_t i, std::int64_t j) const { return table_[lattice_hash(i, j, parameters_.table_bits)]; }

// Perlin(x, y) = sum_k 2^-k Perlin0(2^k x, 2^k y), scaled by amplitude / sum_k 2^-k (paper 3.4).
double PerlinNoise::operator()(double x, double y) const {
  double sum = 0.0;
  double scale = 1.0;  // 2^k, doubled exactly each octave
  for (int k = 0; k < parameters_.octaves; ++k, scale *= 2.0) {
    const double lambda = parameters_.base_frequency * scale;
    const LatticeCell cell = lattice_cell(lambda * x, lambda * y);
    const double a = table_at(cell.i, cell.j);
    const double b = table_at(cell.i + 1, cell.j);
    const double c = table_at(cell.i, cell.j + 1);
    const double d = table_at(cell.i + 1, cell.j + 1);
    const double perlin0 =
        (1.0 - cell.fv) * ((1.0 - cell.fu) * a + cell.fu * b) + cell.fv * ((1.0 - cell.fu) * c + cell.fu * d);
    sum += perlin0 / scale;
  }
  return parameters_.amplitude * octave_norm_ * sum;
}

// Derivative of each bilinear patch in (frac(u), frac(v)), times d(lambda 2^k x)/dx = lambda 2^k;
// with the octave weight 2^-k every octave contributes lambda times its patch slope.
Eigen::Vector2d PerlinNoise::gradient(double x, double y) const {
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  double lambda = parameters_.base_frequency;  // lambda 2^k, doubled exactly each octave
  for (int k = 0; k < parameters_.octaves; ++k, lambda *= 2.0) {
    const LatticeCell cell = lattice_cell(lambda * x, lambda * y);
    const double a = table_at(cell.i, cell.j);
    const double b = table_at(cell.i + 1, cell.j);
    const double c = table_at(cell.i, cell.j + 1);
    const double d = table_at(cell.i + 1, cell.j + 1);
    sum.x() += (1.0 - cell.fv) * (b - a) + cell.fv * (d - c);
    sum.y() += (1.0 - cell.fu) * (c - a) + cell.fu * (d - b);
  }
  return parameters_.amplitude * octave_norm_ * parameters_.base_frequency * sum;
}

}  // namespace talus
