// The structure-of-arrays particle store (paper 4.1).
#include "talus/mudflow/particle_set.hpp"

#include <cassert>

namespace talus {

std::size_t ParticleSet::add(double particle_mass, const Eigen::Vector3d& position, const Eigen::Vector3d& velocity,
                             double support_radius) {
  mass.push_back(particle_mass);
  x.push_back(position.x());
  y.push_back(position.y());
  z.push_back(position.z());
  vx.push_back(velocity.x());
  vy.push_back(velocity.y());
  vz.push_back(velocity.z());
  ax.push_back(0);
  ay.push_back(0);
  az.push_back(0);
  density.push_back(0);
  depth.push_back(0);
  pressure.push_back(0);
  radius.push_back(support_radius);
  still_time.push_back(0);
  level.push_back(0);
  state.push_back(ParticleState::flowing);
  return mass.size() - 1;
}

namespace {

// Applies one selection or permutation to every array of the set.
template <class Pick>
void rebuild_arrays(ParticleSet& p, std::size_t new_size, Pick pick) {
  auto apply = [&](auto& values) {
    std::remove_reference_t<decltype(values)> next(new_size);
    for (std::size_t k = 0; k < new_size; ++k) next[k] = values[pick(k)];
    values.swap(next);
  };
  apply(p.mass);
  apply(p.x);
  apply(p.y);
  apply(p.z);
  apply(p.vx);
  apply(p.vy);
  apply(p.vz);
  apply(p.ax);
  apply(p.ay);
  apply(p.az);
  apply(p.density);
  apply(p.depth);
  apply(p.pressure);
  apply(p.radius);
  apply(p.still_time);
  apply(p.level);
  apply(p.state);
}

}  // namespace

void ParticleSet::keep_only(const std::vector<char>& keep) {
  assert(keep.size() == size());
  std::vector<std::uint32_t> kept;
  kept.reserve(size());
  for (std::size_t i = 0; i < keep.size(); ++i) {
    if (keep[i]) kept.push_back(static_cast<std::uint32_t>(i));
  }
  reorder(kept);
}

void ParticleSet::reorder(const std::vector<std::uint32_t>& order) {
  rebuild_arrays(*this, order.size(), [&](std::size_t k) { return order[k]; });
}

double ParticleSet::total_mass() const {
  double sum = 0;
  for (double m : mass) sum += m;
  return sum;
}

Eigen::Vector3d ParticleSet::total_momentum() const {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = 0; i < size(); ++i) sum += mass[i] * velocity(i);
  return sum;
}

double ParticleSet::kinetic_energy() const {
  double sum = 0;
  for (std::size_t i = 0; i < size(); ++i) sum += 0.5 * mass[i] * velocity(i).squaredNorm();
  return sum;
}

}  // namespace talus
