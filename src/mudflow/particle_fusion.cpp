// Fusion of particles (paper 4.2, fig. 8b): greedy choice of calm, compact, round groups of four
// and their merge into one particle of twice the spacing.
#include "talus/mudflow/particle_fusion.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "talus/mudflow/flow_density.hpp"
#include "talus/mudflow/particle_fission.hpp"
#include "talus/mudflow/smoothing_kernel.hpp"

namespace talus {
namespace {

// Relative tolerance on radii and spacings (-): they are particle_size x 2^k up to rounding.
constexpr double kSizeTolerance = 1e-9;
constexpr std::size_t kGroupSize = 4;
// Largest ratio of the two eigenvalues of a group's spread for a "nearly round" footprint (-).
constexpr double kRoundness = 2;

using Group = std::array<std::uint32_t, kGroupSize>;

// The merged particle of one group, before it is written into the set.
struct Merged {
  Group members{};           // ascending: members[0] is the slot the merged particle takes
  double mass = 0;           // kg
  double x = 0, y = 0;       // m: centre of mass
  Eigen::Vector3d velocity;  // m/s: momentum / mass
};

bool same_radius(double a, double b) { return std::abs(a - b) <= kSizeTolerance * std::max(a, b); }

// Paper 4.2, fig. 8b, the group of i: i and its three nearest flowing neighbours of the same
// radius within its support that are in no group yet, ties by index. Returns false when fewer
// than three exist.
bool nearest_group(const ParticleSet& particles, const PairSearch& search, const std::vector<char>& grouped,
                   std::uint32_t i, Group& group) {
  struct Candidate {
    double distance2;  // m2
    std::uint32_t index;
    bool operator<(const Candidate& other) const {
      return distance2 < other.distance2 || (distance2 == other.distance2 && index < other.index);
    }
  };
  std::array<Candidate, kGroupSize - 1> nearest{};
  std::size_t found = 0;
  const double radius = particles.radius[i];  // m
  for (const std::uint32_t s : search.find_pairs(particles.x[i], particles.y[i], radius, i)) {
    const std::uint32_t j = search.index(s);
    if (grouped[j] || particles.state[j] != ParticleState::flowing) continue;
    if (!same_radius(particles.radius[j], radius)) continue;
    const double dx = search.x(s) - particles.x[i], dy = search.y(s) - particles.y[i];
    const Candidate candidate{dx * dx + dy * dy, j};
    if (found == nearest.size() && !(candidate < nearest.back())) continue;
    // Insertion into the sorted list of the nearest, the farthest dropping out when it is full.
    std::size_t slot = found < nearest.size() ? found++ : nearest.size() - 1;
    for (; slot > 0 && candidate < nearest[slot - 1]; --slot) nearest[slot] = nearest[slot - 1];
    nearest[slot] = candidate;
  }
  if (found < nearest.size()) return false;
  group = {i, nearest[0].index, nearest[1].index, nearest[2].index};
  std::sort(group.begin(), group.end());
  return true;
}

// Whether the merged particle of `group` would sum over at most rule.crowded_radius: twice each
// member's natural smoothing radius, as four times the mass at the same density doubles it.
bool crowded(const ParticleSet& particles, const FusionRule& rule, const Group& group) {
  if (!(rule.crowded_radius > 0)) return false;
  for (std::uint32_t k : group) {
    if (2 * natural_smoothing_radius(particles, k) > rule.crowded_radius) return false;
  }
  return true;
}

// Paper 4.2, fig. 8b, the fusion criterion: the group is calm (every pressure contrast below the
// threshold, every velocity within speed_difference of the mean) or crowded (FusionRule: its
// own threshold, and speeds within a fraction of the group's), compact (every member within
// one spacing of the centre of mass), nearly round (eigenvalues of the mass-weighted spread of
// positions within kRoundness of each other), on the ground, and its merged spacing within
// largest_spacing. Fills `merged` and returns true when all hold.
bool merge_allowed(const ParticleSet& particles, const GroundModel& ground, const std::vector<double>& contrast,
                   const FusionRule& rule, const Group& group, Merged& merged) {
  const std::uint32_t first = group[0];
  const double spacing = particles.radius[first] / kSupportPerSpacing;  // m
  if (2 * spacing > rule.largest_spacing * (1 + kSizeTolerance)) return false;
  const bool is_crowded = crowded(particles, rule, group);
  const double threshold = is_crowded ? rule.crowded_threshold : rule.threshold;  // -
  double mass = 0, offset_x = 0, offset_y = 0;  // kg, kg m, kg m: offsets from the first member
  Eigen::Vector3d momentum = Eigen::Vector3d::Zero();  // kg m/s
  for (std::uint32_t k : group) {
    if (!(contrast[k] < threshold)) return false;
    mass += particles.mass[k];
    offset_x += particles.mass[k] * (particles.x[k] - particles.x[first]);
    offset_y += particles.mass[k] * (particles.y[k] - particles.y[first]);
    momentum += particles.mass[k] * particles.velocity(k);
  }
  const double centre_dx = offset_x / mass, centre_dy = offset_y / mass;  // m, from the first member
  const Eigen::Vector3d velocity = momentum / mass;                      // m/s
  const double speed_tolerance =                                         // m/s
      is_crowded ? std::max(rule.speed_difference, kCrowdedSpeedFraction * velocity.norm()) : rule.speed_difference;
  double spread_xx = 0, spread_yy = 0, spread_xy = 0;                    // m2
  for (std::uint32_t k : group) {
    if ((particles.velocity(k) - velocity).norm() > speed_tolerance) return false;
    const double dx = particles.x[k] - particles.x[first] - centre_dx;
    const double dy = particles.y[k] - particles.y[first] - centre_dy;
    if (std::hypot(dx, dy) > spacing * (1 + kSizeTolerance)) return false;
    spread_xx += particles.mass[k] * dx * dx;
    spread_yy += particles.mass[k] * dy * dy;
    spread_xy += particles.mass[k] * dx * dy;
  }
  const double mean = 0.5 * (spread_xx + spread_yy) / mass;  // m2
  const double half_gap = std::hypot(0.5 * (spread_xx - spread_yy), spread_xy) / mass;  // m2
  if (mean + half_gap > kRoundness * (mean - half_gap)) return false;
  const double centre_x = particles.x[first] + centre_dx, centre_y = particles.y[first] + centre_dy;
  if (!ground.contains(centre_x, centre_y)) return false;
  merged = {group, mass, centre_x, centre_y, velocity};
  return true;
}

// Writes the merged particle into the slot of the group's lowest index: mass, centre of mass on
// the ground, momentum / mass, twice the radius, the smallest level and still time, mass-weighted
// means of acceleration, density, depth and pressure.
void write_merged(ParticleSet& particles, const GroundModel& ground, const Merged& merged) {
  double ax = 0, ay = 0, az = 0, density = 0, depth = 0, pressure = 0;  // mass-weighted sums
  double still_time = particles.still_time[merged.members[0]];           // s
  std::uint8_t level = particles.level[merged.members[0]];
  for (std::uint32_t k : merged.members) {
    const double m = particles.mass[k];
    ax += m * particles.ax[k];
    ay += m * particles.ay[k];
    az += m * particles.az[k];
    density += m * particles.density[k];
    depth += m * particles.depth[k];
    pressure += m * particles.pressure[k];
    still_time = std::min(still_time, particles.still_time[k]);
    level = std::min(level, particles.level[k]);
  }
  const std::uint32_t slot = merged.members[0];
  const double m = merged.mass;
  particles.mass[slot] = m;
  particles.x[slot] = merged.x;
  particles.y[slot] = merged.y;
  particles.z[slot] = ground.elevation(merged.x, merged.y);
  particles.vx[slot] = merged.velocity.x();
  particles.vy[slot] = merged.velocity.y();
  particles.vz[slot] = merged.velocity.z();
  particles.ax[slot] = ax / m;
  particles.ay[slot] = ay / m;
  particles.az[slot] = az / m;
  particles.density[slot] = density / m;
  particles.depth[slot] = depth / m;
  particles.pressure[slot] = pressure / m;
  particles.radius[slot] *= 2;
  particles.still_time[slot] = still_time;
  particles.level[slot] = level;
  particles.state[slot] = ParticleState::flowing;
}

}  // namespace

// Paper 4.2, fig. 8b: groups chosen greedily in index order on the state at the call, then merged.
std::size_t merge_particles(ParticleSet& particles, const PairSearch& search, const GroundModel& ground,
                            const FusionRule& rule) {
  const std::vector<double> contrast = pressure_contrasts(particles, search);
  const std::size_t n = particles.size();
  std::vector<char> grouped(n, 0);
  std::vector<Merged> merges;
  for (std::size_t i = 0; i < n; ++i) {
    if (grouped[i] || particles.state[i] != ParticleState::flowing) continue;
    Group group;
    Merged merged;
    if (!nearest_group(particles, search, grouped, static_cast<std::uint32_t>(i), group)) continue;
    if (!merge_allowed(particles, ground, contrast, rule, group, merged)) continue;
    for (std::uint32_t k : group) grouped[k] = 1;
    merges.push_back(merged);
  }
  if (merges.empty()) return 0;
  std::vector<char> keep(n, 1);
  for (const Merged& merged : merges) {
    write_merged(particles, ground, merged);
    for (std::size_t k = 1; k < kGroupSize; ++k) keep[merged.members[k]] = 0;
  }
  particles.keep_only(keep);
  return merges.size();
}

}  // namespace talus
