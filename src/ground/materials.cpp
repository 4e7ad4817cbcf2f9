// Materials table (paper 2.1): class look-up and the built-in lithology and vegetation classes.
// Lithology codes 0-7 are the Rockyfor3D soil types; every value's source and the impact test
// that checks the stress cycles are in docs/materials.md.
#include "talus/ground/materials.hpp"

#include <algorithm>

namespace talus {

const LithologyClass* MaterialsTable::find_lithology(int code) const {
  const auto found = std::find_if(lithology.begin(), lithology.end(),
                                  [code](const LithologyClass& c) { return c.code == code; });
  return found == lithology.end() ? nullptr : &*found;
}

const VegetationClass* MaterialsTable::find_vegetation(int code) const {
  const auto found = std::find_if(vegetation.begin(), vegetation.end(),
                                  [code](const VegetationClass& c) { return c.code == code; });
  return found == vegetation.end() ? nullptr : &*found;
}

MaterialsTable builtin_materials() {
  MaterialsTable table;
  // Columns: code, name, k1 (Pa/m), yield (Pa), k2 (Pa/m), k3 (Pa/m), sliding friction (tan),
  // rolling friction (tan), restitution normal, restitution tangential, noise amplitude (m).
  // k1: moduli of subgrade reaction (Bowles) or plate-load moduli; yield: presumptive bearing
  // pressures; k2, k3: our choice, checked against the Chant Sura energy ratios; sliding friction:
  // drained friction angles of soils and basic friction angles of rock; rolling friction and
  // tangential restitution: the closest STONE class; normal restitution: Rockyfor3D midpoint.
  table.lithology = {
      {0, "river or swamp", 1.0e7, 5.0e4, 1.0e6, 5.0e7, 0.95, 0.95, 0.0, 0.10, 0.0},
      {1, "fine soil > 1 m", 1.5e7, 2.0e5, 7.0e6, 4.5e7, 0.80, 0.80, 0.23, 0.40, 0.05},
      {2, "fine soil < 1 m, sand or gravel", 3.0e7, 3.0e5, 1.8e7, 8.0e7, 0.65, 0.65, 0.28, 0.55, 0.10},
      {3, "scree, medium compact soil, forest road", 6.0e7, 5.0e5, 4.0e7, 1.3e8, 0.70, 0.35, 0.33, 0.55, 0.15},
      {4, "talus, compact soil with large fragments", 1.0e8, 8.0e5, 7.0e7, 1.9e8, 0.78, 0.40, 0.38, 0.65, 0.30},
      {5, "bedrock with thin weathered cover", 5.0e8, 3.0e6, 3.5e8, 8.0e8, 0.62, 0.35, 0.43, 0.70, 0.10},
      {6, "bedrock", 5.0e9, 2.0e7, 3.5e9, 6.0e9, 0.58, 0.30, 0.53, 0.75, 0.20},
      {7, "asphalt road", 5.0e8, 2.0e6, 3.0e8, 9.0e8, 0.60, 0.35, 0.355, 0.70, 0.0},
  };
  // Deperdition c (1/m): our choice from tree energy-absorption figures (docs/materials.md).
  table.vegetation = {
      {0, "bare", 0.0},
      {1, "meadow", 0.001},
      {2, "shrubs", 0.003},
      {3, "open forest", 0.007},
      {4, "dense forest", 0.015},
  };
  table.default_lithology = 4;
  table.default_vegetation = 0;
  return table;
}

}  // namespace talus
