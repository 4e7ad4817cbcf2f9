// The piston carpet of paper 2.2: soil pistons on a lattice anchored at the CRS origin, cached
// only under the rock's bounding box, with rows and columns added and dropped as the rock moves.
#include "talus/rockfall/piston_carpet.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <utility>

#include "talus/core/errors.hpp"

namespace talus {
namespace {

// Lattice coordinate (m) of index k for spacing s: the one expression every piston and every
// window bound uses, so that membership is decided on the coordinates the pistons carry.
double lattice_coordinate(std::int64_t k, double spacing) { return static_cast<double>(k) * spacing; }

// The lattice indices [begin, end) whose coordinates lie in [low, high] (m), high >= low finite.
// The division gives the answer to within one index; the two loops settle it exactly.
std::pair<std::int64_t, std::int64_t> lattice_range(double low, double high, double spacing) {
  auto begin = static_cast<std::int64_t>(std::ceil(low / spacing));
  while (lattice_coordinate(begin - 1, spacing) >= low) --begin;
  while (lattice_coordinate(begin, spacing) < low) ++begin;
  auto last = static_cast<std::int64_t>(std::floor(high / spacing));
  while (lattice_coordinate(last + 1, spacing) <= high) ++last;
  while (lattice_coordinate(last, spacing) > high) --last;
  return {begin, last + 1};
}

// Paper 2.2: the window of lattice points under the region of interest [x_min, x_max] x
// [y_min, y_max] (m); empty when the region is inverted, not finite, or holds no point.
CarpetWindow window_over(double x_min, double x_max, double y_min, double y_max, double spacing) {
  // Beyond this many spacings from the origin the indices would leave int64 (with margin).
  const double limit = 1e15 * spacing;
  const auto usable = [limit](double low, double high) {
    return low <= high && std::abs(low) < limit && std::abs(high) < limit;
  };
  if (!usable(x_min, x_max) || !usable(y_min, y_max)) return {};
  const auto [i_begin, i_end] = lattice_range(x_min, x_max, spacing);
  const auto [j_begin, j_end] = lattice_range(y_min, y_max, spacing);
  CarpetWindow window{i_begin, i_end, j_begin, j_end};
  return window.empty() ? CarpetWindow{} : window;
}

bool same_window(const CarpetWindow& a, const CarpetWindow& b) {
  return a.i_begin == b.i_begin && a.i_end == b.i_end && a.j_begin == b.j_begin && a.j_end == b.j_end;
}

bool holds(const CarpetWindow& window, std::int64_t i, std::int64_t j) {
  return i >= window.i_begin && i < window.i_end && j >= window.j_begin && j < window.j_end;
}

// Place of lattice (i, j) in a window's row-major (in j) storage; (i, j) must be inside.
std::size_t slot(const CarpetWindow& window, std::int64_t i, std::int64_t j) {
  return static_cast<std::size_t>((j - window.j_begin) * window.columns() + (i - window.i_begin));
}

// As slot(), after checking that the window holds (i, j): std::out_of_range otherwise.
std::size_t checked_slot(const CarpetWindow& window, std::int64_t i, std::int64_t j) {
  if (!holds(window, i, j)) {
    throw std::out_of_range("piston carpet: lattice point (" + std::to_string(i) + ", " + std::to_string(j) +
                            ") is outside the window");
  }
  return slot(window, i, j);
}

}  // namespace

PistonCarpet::PistonCarpet(const PerturbedGround& ground, double spacing) : ground_(&ground), spacing_(spacing) {
  if (!(spacing > 0.0 && std::isfinite(spacing))) {
    throw InputError("piston carpet: the piston spacing must be a positive number of metres, got " +
                     std::to_string(spacing));
  }
}

// Paper 2.2, "rows and columns of pistons are removed or added to the adequate side of the
// carpet": pistons of the old window that the new one still holds move over with their state,
// the others are dropped (their stored elastic energy, J, is returned), and only lattice points
// new to the window are built from the ground.
double PistonCarpet::cover(double x_min, double x_max, double y_min, double y_max) {
  const CarpetWindow window = window_over(x_min, x_max, y_min, y_max, spacing_);
  if (same_window(window, window_)) return 0.0;

  double dropped_energy = 0.0;
  for (const Piston& piston : pistons_) {
    if (!holds(window, piston.i, piston.j)) dropped_energy += stored_energy(piston.cycle, piston.state) * piston.area;
  }

  next_.clear();
  next_.reserve(static_cast<std::size_t>(window.columns() * window.rows()));
  for (std::int64_t j = window.j_begin; j < window.j_end; ++j) {
    for (std::int64_t i = window.i_begin; i < window.i_end; ++i) {
      if (holds(window_, i, j)) {
        next_.push_back(std::move(pistons_[slot(window_, i, j)]));
      } else {
        next_.push_back(make_piston(i, j));
        ++built_;
      }
    }
  }
  pistons_.swap(next_);
  window_ = window;
  return dropped_energy;
}

Piston& PistonCarpet::at(std::int64_t i, std::int64_t j) { return pistons_[checked_slot(window_, i, j)]; }

const Piston& PistonCarpet::at(std::int64_t i, std::int64_t j) const { return pistons_[checked_slot(window_, i, j)]; }

// Paper 2.2 and fig. 3b: the piston at lattice (i, j) stands on the perturbed ground along its
// normal, with the cross-section s^2 / n_z (m2) that its share of the inclined surface has, and
// the stress cycle, friction and vegetation of the interpolated material. Where the ground is
// undefined it is invalid: NaN height, no cross-section, a zero cycle.
Piston PistonCarpet::make_piston(std::int64_t i, std::int64_t j) const {
  Piston piston;
  piston.i = i;
  piston.j = j;
  const double x = lattice_coordinate(i, spacing_);
  const double y = lattice_coordinate(j, spacing_);
  if (!ground_->contains(x, y)) {
    piston.rest_top = Eigen::Vector3d(x, y, std::numeric_limits<double>::quiet_NaN());
    return piston;
  }
  const GroundPoint point = ground_->at(x, y);
  piston.valid = true;
  piston.rest_top = Eigen::Vector3d(x, y, point.height);
  piston.axis = point.normal;
  piston.area = spacing_ * spacing_ / point.normal.z();
  piston.cycle = StressCycle::of(point.material);
  piston.friction = point.material.friction;
  piston.rolling_friction = point.material.rolling_friction;
  piston.vegetation_deperdition = point.material.vegetation_deperdition;
  return piston;
}

}  // namespace talus
