// Tests of the built-in materials table (ground/materials): stress cycles that make sense, codes
// that are unique, defaults that exist, and the class look-up.
#include "talus/ground/materials.hpp"

#include <cstddef>
#include <iterator>
#include <set>

#include <gtest/gtest.h>

namespace talus {
namespace {

TEST(BuiltinMaterials, StressCyclesHaveSoftPlasticAndStiffUnloadingSlopes) {
  for (const LithologyClass& c : builtin_materials().lithology) {
    SCOPED_TRACE(c.name);
    EXPECT_GT(c.plastic_slope, 0.0);
    EXPECT_LT(c.plastic_slope, c.elastic_slope);
    EXPECT_LT(c.elastic_slope, c.unloading_slope);
    EXPECT_GT(c.yield_pressure, 0.0);
  }
}

TEST(BuiltinMaterials, CoefficientsAreWithinTheirRanges) {
  const MaterialsTable table = builtin_materials();
  for (const LithologyClass& c : table.lithology) {
    SCOPED_TRACE(c.name);
    EXPECT_FALSE(c.name.empty());
    EXPECT_GE(c.friction, 0.0);
    EXPECT_GE(c.restitution_normal, 0.0);
    EXPECT_LE(c.restitution_normal, 1.0);
    EXPECT_GE(c.restitution_tangential, 0.0);
    EXPECT_LE(c.restitution_tangential, 1.0);
    EXPECT_GE(c.noise_amplitude, 0.0);
  }
  for (const VegetationClass& c : table.vegetation) {
    SCOPED_TRACE(c.name);
    EXPECT_FALSE(c.name.empty());
    EXPECT_GE(c.deperdition, 0.0);
  }
}

TEST(BuiltinMaterials, LithologyIsTheEightRockyfor3DSoilTypes) {
  std::set<int> codes;
  for (const LithologyClass& c : builtin_materials().lithology) codes.insert(c.code);
  EXPECT_EQ(codes, (std::set<int>{0, 1, 2, 3, 4, 5, 6, 7}));
  EXPECT_EQ(builtin_materials().lithology.size(), 8u);
}

TEST(BuiltinMaterials, VegetationCodesAreUniqueAndDeperditionGrowsWithDensity) {
  const MaterialsTable table = builtin_materials();
  std::set<int> codes;
  for (const VegetationClass& c : table.vegetation) codes.insert(c.code);
  EXPECT_EQ(codes, (std::set<int>{0, 1, 2, 3, 4}));
  EXPECT_EQ(table.vegetation.size(), 5u);
  EXPECT_EQ(table.find_vegetation(0)->deperdition, 0.0);
  for (int code = 1; code <= 4; ++code) {
    EXPECT_GT(table.find_vegetation(code)->deperdition, table.find_vegetation(code - 1)->deperdition) << code;
  }
}

TEST(BuiltinMaterials, NormalRestitutionFollowsTheRockyfor3DOrder) {
  // Rockyfor3D ranges put swamp lowest, then fine soils, scree, asphalt, talus, bedrock.
  const MaterialsTable table = builtin_materials();
  const int order[] = {0, 1, 2, 3, 7, 4, 5, 6};
  for (std::size_t k = 1; k < std::size(order); ++k) {
    const double before = table.find_lithology(order[k - 1])->restitution_normal;
    EXPECT_LT(before, table.find_lithology(order[k])->restitution_normal) << order[k - 1] << " before " << order[k];
  }
  EXPECT_EQ(table.find_lithology(0)->restitution_normal, 0.0);
}

TEST(BuiltinMaterials, DefaultsAreTalusAndBareGround) {
  const MaterialsTable table = builtin_materials();
  EXPECT_EQ(table.default_lithology, 4);
  EXPECT_EQ(table.default_vegetation, 0);
  ASSERT_NE(table.find_lithology(table.default_lithology), nullptr);
  ASSERT_NE(table.find_vegetation(table.default_vegetation), nullptr);
  EXPECT_EQ(table.find_lithology(4)->name, "talus, compact soil with large fragments");
  EXPECT_EQ(table.find_vegetation(0)->name, "bare");
}

TEST(MaterialsTable, FindReturnsTheClassWithThatCodeOrNull) {
  MaterialsTable table;
  table.lithology = {{12, "clay", 1, 1, 1, 1, 0, 0, 0, 0, 0}, {3, "sand", 2, 2, 2, 2, 0, 0, 0, 0, 0}};
  table.vegetation = {{5, "reeds", 0.5}};
  ASSERT_NE(table.find_lithology(3), nullptr);
  EXPECT_EQ(table.find_lithology(3)->name, "sand");
  EXPECT_EQ(table.find_lithology(12), &table.lithology[0]);
  EXPECT_EQ(table.find_lithology(4), nullptr);
  EXPECT_EQ(table.find_vegetation(5), &table.vegetation[0]);
  EXPECT_EQ(table.find_vegetation(0), nullptr);
}

}  // namespace
}  // namespace talus
