// The piston carpet of paper 2.2 (docs/architecture.md section 2): the refined ground model exists only as
// a fine grid of soil pistons under the vertical projection of the rock's bounding box. Pistons
// sit on a lattice anchored at the CRS origin (piston (i, j) at x = i s, y = j s for spacing s),
// so a piston is the same object whichever carpet window holds it. Each piston stands along the
// local normal of the perturbed ground at its lattice point, has a cross-section of s^2 / n_z
// (its share of the inclined surface) and its own stress cycle (stress_cycle.hpp). When the rock
// moves, cover() drops the rows and columns that left the region and adds the new ones; pistons
// that stay keep their state (temporal coherence). Cost grows with the rock's size, never with
// the DEM's.
#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "talus/ground/perturbed_ground.hpp"
#include "talus/ground/stress_cycle.hpp"

namespace talus {

struct Piston {
  std::int64_t i = 0, j = 0;                             // lattice indices
  bool valid = false;                                    // false where the ground is undefined (nodata, outside the DEM):
                                                         // then rest_top.z is NaN (never inside a rock), area 0 and
                                                         // the cycle all zero (no force)
  Eigen::Vector3d rest_top = Eigen::Vector3d::Zero();    // m: the undeformed ground surface point
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();       // unit upward normal of the perturbed ground there
  double area = 0;                                       // m2: cross-section s^2 / axis.z
  StressCycle cycle;                                     // from the interpolated material
  double friction = 0;                                   // Coulomb mu (-), with the trajectory's variation
  double rolling_friction = 0;                           // rolling mu_r (-), with the trajectory's variation
  double vegetation_deperdition = 0;                     // c (1/m)
  PistonState state;
  // Top of the piston (m): rest_top moved down its axis by the compression.
  Eigen::Vector3d top() const { return rest_top - state.compression * axis; }
};

// Lattice window [i_begin, i_end) x [j_begin, j_end).
struct CarpetWindow {
  std::int64_t i_begin = 0, i_end = 0, j_begin = 0, j_end = 0;
  bool empty() const { return i_begin >= i_end || j_begin >= j_end; }
  std::int64_t columns() const { return i_end - i_begin; }
  std::int64_t rows() const { return j_end - j_begin; }
};

class PistonCarpet {
 public:
  // ground must outlive the carpet; spacing s (m) > 0 and finite, InputError otherwise.
  PistonCarpet(const PerturbedGround& ground, double spacing);

  // Makes the carpet cover every lattice point in [x_min, x_max] x [y_min, y_max] (m) and no
  // other (a point is inside when its coordinates i s, j s, as computed in doubles, are), keeps
  // the pistons already there with their state, drops the others, adds new ones. An inverted
  // or non-finite rectangle gives an empty window. An unchanged window costs a few operations;
  // otherwise kept pistons are moved without asking the ground, and only new ones are built.
  // Returns the elastic energy (J) still stored in dropped pistons, which the caller books as
  // deformation loss (zero when the region covers the rock's whole footprint).
  double cover(double x_min, double x_max, double y_min, double y_max);

  double spacing() const { return spacing_; }
  const CarpetWindow& window() const { return window_; }
  std::size_t size() const { return pistons_.size(); }
  // Piston at lattice (i, j) inside the window; throws std::out_of_range outside it.
  Piston& at(std::int64_t i, std::int64_t j);
  const Piston& at(std::int64_t i, std::int64_t j) const;
  // All pistons of the window, in an unspecified but deterministic order.
  std::vector<Piston>& pistons() { return pistons_; }
  const std::vector<Piston>& pistons() const { return pistons_; }

  // Pistons built from the ground since construction (a measure of the carpet's cost).
  std::uint64_t pistons_built() const { return built_; }

 private:
  Piston make_piston(std::int64_t i, std::int64_t j) const;
  const PerturbedGround* ground_;  // a pointer, so that a run can keep a copy of its carpet and restore it
  double spacing_;
  CarpetWindow window_;
  std::vector<Piston> pistons_;   // window_.columns() x window_.rows(), row-major in j
  std::vector<Piston> next_;      // scratch for cover(), kept to reuse its allocation
  std::uint64_t built_ = 0;
};

}  // namespace talus
