// Materials (paper 2.1): what each lithology class and vegetation class of the maps means for
// the ground model. Parameters are data; units in comments. Defaults and their sources:
// docs/materials.md.
#pragma once

#include <string>
#include <vector>

namespace talus {

// One lithology class: the stress cycle of paper fig. 2, the sliding and rolling friction, plus the
// fast-mode coefficients.
// Pressures act on a piston's cross-section; compressions are along the piston axis.
struct LithologyClass {
  int code = 0;                         // value in the lithology raster
  std::string name;
  double elastic_slope = 0;             // k1: loading pressure per compression (Pa/m)
  double yield_pressure = 0;            // pressure where plastic deformation starts (Pa)
  double plastic_slope = 0;             // k2 < k1: plastic loading slope (Pa/m)
  double unloading_slope = 0;           // k3 > k1: unloading and reloading slope (Pa/m)
  double friction = 0;                  // sliding (Coulomb) friction coefficient mu = tan(angle) (-)
  double rolling_friction = 0;          // rolling friction coefficient mu_r (Azzoni et al. 1995) (-)
  double restitution_normal = 0;        // fast mode: normal velocity kept at an impact (-)
  double restitution_tangential = 0;    // fast mode: tangential velocity kept at an impact (-)
  double noise_amplitude = 0;           // Perlin roughness amplitude of paper 3.4 (m)
};

// One vegetation class: the energy deperdition coefficient of paper 2.1 (last paragraph).
// In contact, vegetation decelerates a rock by c |v| v, so its kinetic energy decays as
// exp(-2 c s) over a travelled distance s.
struct VegetationClass {
  int code = 0;                         // value in the vegetation raster
  std::string name;
  double deperdition = 0;               // c (1/m)
};

struct MaterialsTable {
  std::vector<LithologyClass> lithology;
  std::vector<VegetationClass> vegetation;
  int default_lithology = 0;            // class used where no lithology raster is given
  int default_vegetation = 0;           // class used where no vegetation raster is given

  const LithologyClass* find_lithology(int code) const;    // nullptr when absent
  const VegetationClass* find_vegetation(int code) const;  // nullptr when absent
};

// The built-in table (Rockyfor3D soil types 0-7 as lithology, bare/meadow/shrub/forest as
// vegetation); docs/materials.md gives every value's source.
MaterialsTable builtin_materials();

}  // namespace talus
