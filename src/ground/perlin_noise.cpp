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

constexpr std::uint64_t kHashX = 0x9E3779B97F4A7C15ULL;
constexpr std::uint64_t kHashY = 0xD1B54A32D192ED03ULL;

// Hash(i, j) from its combination h = i kHashX + j kHashY (odd multipliers, two's complement, so
// negative coordinates are fine): one xor-shift-multiply-xor-shift round (a single round of the
// mixers of Steele et al.'s SplitMix64 family), whose top table_bits bits index Tab[].
// Neighbouring lattice points differ in h by kHashX or kHashY, so the four corners of a square
// share one combination. The round's last step, h ^= h >> 32, leaves the top 32 bits of h as
// they are, and table_bits <= 20 reads no others: the index is the product's top bits.
std::size_t finalised_hash(std::uint64_t h, int table_bits) {
  h ^= h >> 32;
  h *= 0xD6E8FEB86659FD93ULL;
  return static_cast<std::size_t>(h >> (64 - table_bits));
}

// E(u): the integral part, floor(u), for |u| < 2^63 without a libm call.
std::int64_t integral_part(double u) {
  const auto truncated = static_cast<std::int64_t>(u);
  return u < static_cast<double>(truncated) ? truncated - 1 : truncated;
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

// One Perlin0 lattice square at scaled coordinates (u, v) = (lambda x, lambda y) (paper 3.4):
// A = Tab[Hash(E(u), E(v))], B = Tab[Hash(E(u) + 1, E(v))], C = Tab[Hash(E(u), E(v) + 1)],
// D = Tab[Hash(E(u) + 1, E(v) + 1)], and frac(u), frac(v).
struct PerlinNoise::Corners {
  double a, b, c, d, fu, fv;
  // Perlin0 = BilinearInterpol(A, B, C, D, frac(u), frac(v)).
  double perlin0() const { return (1.0 - fv) * ((1.0 - fu) * a + fu * b) + fv * ((1.0 - fu) * c + fu * d); }
};

PerlinNoise::Corners PerlinNoise::corners(double u, double v) const {
  const std::int64_t i = integral_part(u);
  const std::int64_t j = integral_part(v);
  const std::uint64_t h = static_cast<std::uint64_t>(i) * kHashX + static_cast<std::uint64_t>(j) * kHashY;
  const int bits = parameters_.table_bits;
  return {table_[finalised_hash(h, bits)],
          table_[finalised_hash(h + kHashX, bits)],
          table_[finalised_hash(h + kHashY, bits)],
          table_[finalised_hash(h + kHashX + kHashY, bits)],
          u - static_cast<double>(i),
          v - static_cast<double>(j)};
}

// Perlin(x, y) = sum_k 2^-k Perlin0(2^k x, 2^k y), scaled by amplitude / sum_k 2^-k (paper 3.4).
double PerlinNoise::operator()(double x, double y) const {
  double sum = 0.0;
  double scale = 1.0;  // 2^k, doubled exactly each octave
  double weight = 1.0;  // 2^-k, halved exactly each octave
  for (int k = 0; k < parameters_.octaves; ++k, scale *= 2.0, weight *= 0.5) {
    const double lambda = parameters_.base_frequency * scale;
    const Corners q = corners(lambda * x, lambda * y);
    sum += weight * q.perlin0();
  }
  return parameters_.amplitude * octave_norm_ * sum;
}

// The value as operator(), and the derivative of each bilinear patch in (frac(u), frac(v)) times
// d(lambda 2^k x)/dx = lambda 2^k: with the octave weight 2^-k every octave contributes lambda
// times its patch slope.
NoiseSample PerlinNoise::sample(double x, double y) const {
  double sum = 0.0;
  Eigen::Vector2d slope_sum = Eigen::Vector2d::Zero();
  double scale = 1.0;  // 2^k, doubled exactly each octave
  double weight = 1.0;  // 2^-k, halved exactly each octave
  for (int k = 0; k < parameters_.octaves; ++k, scale *= 2.0, weight *= 0.5) {
    const double lambda = parameters_.base_frequency * scale;
    const Corners q = corners(lambda * x, lambda * y);
    sum += weight * q.perlin0();
    slope_sum.x() += (1.0 - q.fv) * (q.b - q.a) + q.fv * (q.d - q.c);
    slope_sum.y() += (1.0 - q.fu) * (q.c - q.a) + q.fu * (q.d - q.b);
  }
  const double norm = parameters_.amplitude * octave_norm_;
  return {norm * sum, norm * parameters_.base_frequency * slope_sum};
}

}  // namespace talus
