// Building the scene from the user's files (docs/architecture.md sections 1 and 3).
#include "talus/gis/scene.hpp"

#include <ogrsf_frmts.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <stdexcept>

#include "talus/core/errors.hpp"
#include "talus/gis/gdal_dataset.hpp"
#include "talus/gis/materials_file.hpp"
#include "talus/gis/raster_alignment.hpp"
#include "talus/gis/release_reader.hpp"

namespace talus::gis {
namespace {

std::string join_codes(const std::set<long>& codes, std::size_t limit) {
  std::ostringstream text;
  std::size_t shown = 0;
  for (long code : codes) {
    if (shown == limit) {
      text << ", ... (" << codes.size() << " in all)";
      break;
    }
    text << (shown++ ? ", " : "") << code;
  }
  return text.str();
}

template <class Class>
std::set<long> table_codes(const std::vector<Class>& classes) {
  std::set<long> codes;
  for (const auto& c : classes) codes.insert(c.code);
  return codes;
}

std::string materials_name(const SceneInputs& inputs) {
  return inputs.materials.empty() ? std::string("the built-in materials table") : inputs.materials.string();
}

// Class codes of an aligned raster; cells without a value (on valid terrain) take the
// default class. Codes absent from the table are an error naming them.
Grid<int> class_map(const AlignedRaster& raster, const Grid<double>& dem, const std::set<long>& known, int default_code,
                    const std::string& name, const std::string& table, std::vector<std::string>& problems) {
  GridSpec spec = dem.spec();
  spec.nodata = -1;
  Grid<int> classes(spec, default_code);
  std::set<long> unknown;
  std::size_t missing = 0;
  for (std::size_t i = 0; i < classes.size(); ++i) {
    if (!dem.is_valid(i)) continue;
    if (!raster.values.is_valid(i)) {
      ++missing;
      continue;
    }
    const double value = raster.values[i];
    const long code = std::lround(value);
    if (std::abs(value - static_cast<double>(code)) > 1e-6 || !known.contains(code)) {
      unknown.insert(code);
      continue;
    }
    classes[i] = static_cast<int>(code);
  }
  if (!unknown.empty()) {
    throw InputError(name + ": class codes " + join_codes(unknown, 10) + " are not in " + table + " (known: " +
                     join_codes(known, 20) + ")");
  }
  if (missing > 0) {
    problems.push_back(name + ": " + std::to_string(missing) + " cells of valid terrain have no value; they take the default class " +
                       std::to_string(default_code));
  }
  return classes;
}

// A vegetation raster holds classes when it stores integers, or when every value is a
// whole number found in the table; otherwise its values are deperdition coefficients (1/m).
bool holds_classes(const AlignedRaster& raster, const std::set<long>& known) {
  if (raster.integer_type) return true;
  for (std::size_t i = 0; i < raster.values.size(); ++i) {
    if (!raster.values.is_valid(i)) continue;
    const double v = raster.values[i];
    if (v != std::round(v) || !known.contains(std::lround(v))) return false;
  }
  return true;
}

void load_vegetation(Scene& scene, const CrsOption& crs) {
  const auto& inputs = scene.inputs;
  const Grid<double>& dem = scene.dem.elevation;
  GridSpec spec = dem.spec();
  const VegetationClass* fallback = scene.materials.find_vegetation(scene.materials.default_vegetation);
  scene.vegetation = Grid<double>(spec, fallback->deperdition);
  if (inputs.vegetation.empty()) {
    scene.notes.push_back("vegetation: none given; default class " + std::to_string(fallback->code) + " (" +
                          fallback->name + ") everywhere");
    return;
  }
  const std::string name = describe_input(inputs.vegetation, "vegetation");
  const auto known = table_codes(scene.materials.vegetation);
  // Read once as classes (nearest/mode); continuous coefficients are re-read bilinearly.
  AlignedRaster raster = align_raster(inputs.vegetation, "vegetation", spec, ValueKind::classes, crs);
  if (holds_classes(raster, known)) {
    scene.vegetation_classes = class_map(raster, dem, known, scene.materials.default_vegetation, name,
                                         materials_name(inputs), scene.problems);
    for (std::size_t i = 0; i < scene.vegetation.size(); ++i) {
      scene.vegetation[i] = scene.materials.find_vegetation((*scene.vegetation_classes)[i])->deperdition;
    }
    scene.notes.push_back("vegetation: class codes, aligned by " + raster.method);
    return;
  }
  raster = align_raster(inputs.vegetation, "vegetation", spec, ValueKind::continuous, crs);
  std::size_t missing = 0;
  for (std::size_t i = 0; i < scene.vegetation.size(); ++i) {
    if (!dem.is_valid(i)) continue;
    if (!raster.values.is_valid(i)) {
      ++missing;
      continue;
    }
    if (raster.values[i] < 0.0) throw InputError(name + ": negative deperdition coefficient " + std::to_string(raster.values[i]));
    scene.vegetation[i] = raster.values[i];
  }
  scene.notes.push_back("vegetation: continuous deperdition coefficients (1/m), aligned by " + raster.method);
  if (missing > 0) {
    scene.problems.push_back(name + ": " + std::to_string(missing) + " cells of valid terrain have no value; they take " +
                             std::to_string(fallback->deperdition) + " 1/m");
  }
}

// Mud flow releases the depth given per feature (docs/architecture.md section 3, --release; docs/inputs.md,
// "Release depth"): every layer of a vector release needs the depth attribute, and every
// feature a non-zero value in it. A raster release carries its depths in its values; one whose
// release cells all hold 1 is a mask, refused. With a uniform depth (--depth) nothing is needed.
void require_release_depths(const std::filesystem::path& path, const ReleaseDepthSource& source,
                            const ReleaseSet& release) {
  if (source.uniform) return;
  const std::string name = describe_input(path, "release");
  GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!dataset) {
    const bool mask = std::all_of(release.depth.values().begin(), release.depth.values().end(),
                                  [](float depth) { return depth == 0.0f || depth == 1.0f; });
    if (mask) {
      throw InputError(name + ": holds only 0 and 1, a mask, not depths; give the release depth with --depth M "
                              "(m), or a raster of depths (m)");
    }
    const float deepest = *std::max_element(release.depth.values().begin(), release.depth.values().end());
    if (deepest > kMaxReleaseDepth) {
      std::ostringstream message;
      message << name << ": a release depth of " << deepest << " m; expected depths of at most " << kMaxReleaseDepth
              << " m (are they in centimetres?)";
      throw InputError(message.str());
    }
    return;
  }
  for (OGRLayer* layer : dataset->GetLayers()) {
    const std::string layer_name = layer->GetName();
    const int depth_field = layer->GetLayerDefn()->GetFieldIndex(source.field.c_str());
    if (depth_field < 0) {
      throw InputError(name + ": layer '" + layer_name + "' has no `" + source.field +
                       "` attribute; a mud-flow release needs the release depth (m) of each polygon or point: name "
                       "its attribute with --depth-field NAME, or give one depth with --depth M");
    }
    for (auto& feature : *layer) {
      const OGRGeometry* geometry = feature->GetGeometryRef();
      if (geometry == nullptr || geometry->IsEmpty()) continue;
      if (!feature->IsFieldSetAndNotNull(depth_field) || feature->GetFieldAsDouble(depth_field) == 0.0) {
        throw InputError(name + ": feature " + std::to_string(feature->GetFID()) + " of layer '" + layer_name +
                         "' has no release depth (`" + source.field + "` is empty or 0 m)");
      }
      const double depth = std::abs(feature->GetFieldAsDouble(depth_field));
      if (!(depth <= kMaxReleaseDepth)) {  // also NaN and infinity
        std::ostringstream message;
        message << name << ": feature " << feature->GetFID() << " of layer '" << layer_name << "' has a release depth ("
                << source.field << ") of " << feature->GetFieldAsDouble(depth_field) << " m; expected at most "
                << kMaxReleaseDepth << " m";
        throw InputError(message.str());
      }
    }
  }
}

// The erodible depth (m) per DEM cell, aligned bilinearly (continuous values); negative,
// nodata and off-terrain cells hold no material.
Grid<float> load_erodible(Scene& scene, const CrsOption& crs) {
  const Grid<double>& dem = scene.dem.elevation;
  const std::string name = describe_input(scene.inputs.erodible, "erodible");
  const AlignedRaster raster = align_raster(scene.inputs.erodible, "erodible", dem.spec(), ValueKind::continuous, crs);
  Grid<float> erodible(dem.spec(), 0.0f);
  std::size_t cells = 0, negative = 0;
  double volume = 0;  // m3
  for (std::size_t i = 0; i < erodible.size(); ++i) {
    if (!dem.is_valid(i) || !raster.values.is_valid(i)) continue;
    if (raster.values[i] < 0.0) {
      ++negative;
      continue;
    }
    erodible[i] = static_cast<float>(raster.values[i]);
    if (erodible[i] > 0.0f) {
      ++cells;
      volume += static_cast<double>(erodible[i]) * dem.spec().cell_area();
    }
  }
  std::ostringstream note;
  note << "erodible: " << cells << " cells, " << std::lround(volume) << " m3 of material, aligned by " << raster.method;
  scene.notes.push_back(note.str());
  if (negative > 0) {
    scene.problems.push_back(name + ": " + std::to_string(negative) + " cells hold negative depths; they count as no material");
  }
  if (cells == 0) {
    scene.problems.push_back(name + ": no cell of valid terrain holds erodible material (every value is 0, negative or nodata)");
  }
  return erodible;
}

}  // namespace

GroundModel Scene::ground_model() const {
  Grid<GroundMaterial> nodes(dem.elevation.spec());
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    nodes[i] = GroundMaterial::from(*materials.find_lithology(lithology[i]), vegetation[i]);
  }
  return GroundModel(dem.elevation, std::move(nodes));
}

namespace {

// The DEM and the materials table: what the region of a tiled run holds whole.
Scene load_dem_and_materials(const SceneInputs& inputs, const CrsOption& crs) {
  Scene scene;
  scene.inputs = inputs;
  scene.dem = read_dem(inputs.dem, crs);
  scene.notes.insert(scene.notes.end(), scene.dem.notes.begin(), scene.dem.notes.end());
  scene.materials = inputs.materials.empty() ? builtin_materials() : read_materials(inputs.materials);
  const Grid<double>& dem = scene.dem.elevation;
  std::size_t holes = 0;
  for (std::size_t i = 0; i < dem.size(); ++i) holes += dem.is_valid(i) ? 0 : 1;
  if (holes > 0) {
    scene.notes.push_back(std::to_string(holes) + " DEM cells are nodata: rocks and flows stop there, layers are nodata there");
  }
  return scene;
}

// Lithology and vegetation aligned onto the scene's DEM grid (a window of it, for a tile).
void load_ground_maps(Scene& scene, const CrsOption& crs) {
  const SceneInputs& inputs = scene.inputs;
  const Grid<double>& dem = scene.dem.elevation;
  if (inputs.lithology.empty()) {
    const LithologyClass* fallback = scene.materials.find_lithology(scene.materials.default_lithology);
    scene.lithology = Grid<int>(dem.spec(), fallback->code);
    scene.notes.push_back("lithology: none given; default class " + std::to_string(fallback->code) + " (" +
                          fallback->name + ") everywhere");
  } else {
    const AlignedRaster raster = align_raster(inputs.lithology, "lithology", dem.spec(), ValueKind::classes, crs);
    scene.lithology = class_map(raster, dem, table_codes(scene.materials.lithology), scene.materials.default_lithology,
                                describe_input(inputs.lithology, "lithology"), materials_name(inputs), scene.problems);
    scene.notes.push_back("lithology: aligned by " + raster.method);
  }
  load_vegetation(scene, crs);
}

void load_release(Scene& scene, const CrsOption& crs) {
  const SceneInputs& inputs = scene.inputs;
  if (inputs.release.empty()) return;
  scene.release = read_release(inputs.release, scene.dem.elevation, crs, inputs.run_rock, inputs.release_depth);
  if (inputs.release_needs_depth) require_release_depths(inputs.release, inputs.release_depth, *scene.release);
}

}  // namespace

Scene load_scene(const SceneInputs& inputs) {
  Scene scene = load_region(inputs);
  add_ground_maps(scene);
  return scene;
}

Scene load_region(const SceneInputs& inputs) {
  const CrsOption crs = parse_crs_option(inputs.crs);
  Scene scene = load_dem_and_materials(inputs, crs);
  load_release(scene, crs);
  return scene;
}

void add_ground_maps(Scene& scene) {
  const CrsOption crs = parse_crs_option(scene.inputs.crs);
  load_ground_maps(scene, crs);
  if (!scene.inputs.erodible.empty()) scene.erodible = load_erodible(scene, crs);
}

Scene load_tile(const Scene& region, const GridSpec& window) {
  const Grid<double>& whole = region.dem.elevation;
  if (!window.is_window() || !window.whole().same_grid(whole.spec())) {
    throw std::invalid_argument("load_tile: not a window of the region's DEM");
  }
  Scene tile;
  tile.inputs = region.inputs;
  tile.inputs.release.clear();
  tile.materials = region.materials;
  tile.dem.crs_name = region.dem.crs_name;
  std::vector<double> elevations;
  elevations.reserve(window.cell_count());
  for (int row = 0; row < window.height; ++row) {
    const auto first = whole.values().begin() + static_cast<std::ptrdiff_t>(whole.index(window.col_offset, window.row_offset + row));
    elevations.insert(elevations.end(), first, first + window.width);
  }
  tile.dem.elevation = Grid<double>(window, std::move(elevations));
  add_ground_maps(tile);
  return tile;
}

}  // namespace talus::gis
