// Release of the mud (issue 5, docs/architecture.md section 3 --release): each release cell's column of
// depth d (m) becomes particles of the chosen spacing, laid on a square lattice inside the cell
// and jittered by counter-based random numbers of (seed, cell), so the same seed gives the same
// particles whatever the thread count. A release point releases one DEM cell around it.
// The depth is the thickness normal to the ground (the thin-layer convention of Savage & Hutter
// and com1DFA), a cell releasing rho0 d A / cos(theta) (kg), A the cell's horizontal area (m2) and
// theta the slope at its centre; or, by choice, the height of a vertical column, rho0 d A.
#pragma once

#include <cstdint>
#include <string>

#include "talus/core/release.hpp"
#include "talus/ground/ground_model.hpp"
#include "talus/mudflow/particle_set.hpp"

namespace talus {

// How a release depth is measured (docs/inputs.md, "Release").
enum class ReleaseThickness {
  normal,    // normal to the ground: the column's thickness, as the flow depths are
  vertical,  // vertically: the height of the column over the horizontal cell
};
const char* to_string(ReleaseThickness thickness);  // "normal", "vertical"

// What the user asked for ([mud] release_thickness): one convention, or `auto`, which takes a
// raster of negative depths (the surface lowering of a DEM of difference) as vertical and every
// other release as normal to the ground.
enum class ReleaseThicknessChoice { automatic, normal, vertical };
// "auto", "normal", "vertical"; throws InputError naming the text otherwise.
ReleaseThicknessChoice parse_release_thickness(const std::string& text);
const char* to_string(ReleaseThicknessChoice choice);
ReleaseThickness thickness_for_release(ReleaseThicknessChoice choice, const ReleaseSet& release);

struct ReleaseLayout {
  double spacing = 2.5;          // m: particle spacing (the particle size)
  double mud_density = 2000;     // kg/m3
  double jitter = 0.25;          // fraction of the spacing by which places are shifted at random (-), in [0, 1]
  std::uint64_t seed = 1;
  ReleaseThickness thickness = ReleaseThickness::normal;
};

// Particles at rest for the release, in cell index order, then the points in their order.
// Each released cell (depth > 0, valid DEM node) gets n_x x n_y lattice places, n = max(1,
// round(cell side / spacing)) per axis, each shifted by up to +-jitter / 2 of the lattice step
// per axis with CounterRandom(seed, cell index, place index); a place off the ground surface
// falls back to its lattice point and is dropped if that is off too; the cell's mass rho0 d A
// (normal thickness: rho0 d A / cos(theta), theta at the cell centre; a point takes the cell
// under it) is shared equally by its places. Support radius: kSupportPerSpacing x sqrt(step_x step_y).
// A point with depth > 0 is a cell-sized square centred on it (random source: cell count +
// point index). Masses sum to rho0 x the released volume up to rounding (cells outside the
// ground model's valid area release nothing). release.depth must be on the DEM grid (or
// empty); throws GridMismatch otherwise and InputError for a layout out of range.
ParticleSet release_particles(const GroundModel& ground, const ReleaseSet& release, const ReleaseLayout& layout);

// The volume (m3) of the release's columns under a convention: d A per released cell, divided by
// cos(theta) at the cell's centre for the thickness normal to the ground; a point counts the cell
// under it. The volume release_particles releases, but for places that fall off the ground.
double release_volume(const GroundModel& ground, const ReleaseSet& release, ReleaseThickness thickness);

}  // namespace talus
