// The scene (docs/architecture.md section 1, "data flows one way"): the user's files read, checked and
// aligned onto the DEM grid, ready to become the engine's ground model and release set.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "talus/core/release.hpp"
#include "talus/ground/ground_model.hpp"
#include "talus/ground/materials.hpp"
#include "talus/gis/dem_reader.hpp"
#include "talus/gis/release_reader.hpp"
#include "talus/rockfall/rock.hpp"

namespace talus::gis {

struct SceneInputs {
  std::filesystem::path dem;
  std::filesystem::path lithology;   // empty: the materials' default class everywhere
  std::filesystem::path vegetation;  // empty: the materials' default class everywhere
  std::filesystem::path release;     // empty: no release (talus info only)
  std::filesystem::path erodible;    // empty: no erodible material (mud flow, --erodible)
  std::filesystem::path materials;   // empty: the built-in table
  std::string crs;                   // the --crs text, empty for the files' own
  // Mud flow: every polygon or point of a vector release must carry a non-zero depth (m) in the
  // attribute release_depth.field, and a raster release must hold depths, not a 0/1 mask,
  // unless release_depth.uniform gives one depth for all; a layer without the attribute is
  // refused instead of releasing the default 1 m.
  bool release_needs_depth = false;
  ReleaseDepthSource release_depth;
  // Rock fall: the run's rock; the release features' rock-fall attributes (shape, block_size,
  // density or mass, vx, vy, vz, release_height) are read and checked against it. Empty: they
  // are not read (mud flow, info).
  std::optional<Rock> run_rock;
};

struct Scene {
  SceneInputs inputs;
  DemInput dem;
  MaterialsTable materials;
  Grid<int> lithology;               // class code per cell
  Grid<double> vegetation;           // deperdition coefficient c per cell (1/m)
  std::optional<Grid<int>> vegetation_classes;  // class codes, when the raster holds classes
  std::optional<ReleaseSet> release;
  std::optional<Grid<float>> erodible;  // m of erodible material per cell (0 where none), with --erodible
  std::vector<std::string> notes;    // what was done to the inputs (alignment, reprojection)
  std::vector<std::string> problems; // what the user should look at; not fatal

  // The bilinear ground model of paper 2.2 built from the aligned maps.
  GroundModel ground_model() const;
};

// Reads and aligns every input; throws InputError with one line naming the file and problem.
// The erodible raster holds depths (m) and is aligned bilinearly like vegetation coefficients;
// its negative and nodata values count as no material.
Scene load_scene(const SceneInputs& inputs);

// load_scene in parts, for regions larger than memory (issue 19, item 4; docs/study.md,
// "Tiles"). load_region reads the DEM whole, the materials and the release; add_ground_maps
// reads lithology, vegetation and erodible material onto the scene's DEM grid; load_tile makes
// the scene of one window of the region's DEM grid (GridSpec::window): its elevations cut from
// the region's, its other maps read and aligned for the window alone, no release. Each cell holds
// what load_scene gives it, so a tile's ground model agrees with the whole one on the window.
Scene load_region(const SceneInputs& inputs);
void add_ground_maps(Scene& scene);
Scene load_tile(const Scene& region, const GridSpec& window);

}  // namespace talus::gis
