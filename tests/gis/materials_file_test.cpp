// Materials tables in TOML (gis/materials_file): round trips, the documented default file, and
// one test per kind of bad input, each expecting a one-line InputError naming file and problem.
#include "talus/gis/materials_file.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <ostream>
#include <string>
#include <vector>

#include "talus/core/errors.hpp"
#include "test_paths.hpp"

namespace talus::gis {
namespace {

void expect_same(const MaterialsTable& actual, const MaterialsTable& expected) {
  EXPECT_EQ(actual.default_lithology, expected.default_lithology);
  EXPECT_EQ(actual.default_vegetation, expected.default_vegetation);
  ASSERT_EQ(actual.lithology.size(), expected.lithology.size());
  for (std::size_t k = 0; k < expected.lithology.size(); ++k) {
    const LithologyClass& a = actual.lithology[k];
    const LithologyClass& e = expected.lithology[k];
    SCOPED_TRACE("lithology " + e.name);
    EXPECT_EQ(a.code, e.code);
    EXPECT_EQ(a.name, e.name);
    EXPECT_EQ(a.elastic_slope, e.elastic_slope);
    EXPECT_EQ(a.yield_pressure, e.yield_pressure);
    EXPECT_EQ(a.plastic_slope, e.plastic_slope);
    EXPECT_EQ(a.unloading_slope, e.unloading_slope);
    EXPECT_EQ(a.friction, e.friction);
    EXPECT_EQ(a.rolling_friction, e.rolling_friction);
    EXPECT_EQ(a.restitution_normal, e.restitution_normal);
    EXPECT_EQ(a.restitution_tangential, e.restitution_tangential);
    EXPECT_EQ(a.noise_amplitude, e.noise_amplitude);
  }
  ASSERT_EQ(actual.vegetation.size(), expected.vegetation.size());
  for (std::size_t k = 0; k < expected.vegetation.size(); ++k) {
    SCOPED_TRACE("vegetation " + expected.vegetation[k].name);
    EXPECT_EQ(actual.vegetation[k].code, expected.vegetation[k].code);
    EXPECT_EQ(actual.vegetation[k].name, expected.vegetation[k].name);
    EXPECT_EQ(actual.vegetation[k].deperdition, expected.vegetation[k].deperdition);
  }
}

std::filesystem::path write_file(const std::string& folder, const std::string& text) {
  const auto path = test::fresh_folder(folder) / "materials.toml";
  std::ofstream(path) << text;
  return path;
}

TEST(MaterialsFile, BuiltinTableReadsBackIdentically) {
  const MaterialsTable builtin = builtin_materials();
  const auto path = write_file("materials_builtin_round_trip", materials_to_toml(builtin));
  expect_same(read_materials(path), builtin);
}

TEST(MaterialsFile, AwkwardNumbersAndNamesReadBackIdentically) {
  MaterialsTable table;
  // Shortest round-trip digits, a subnormal and the ends of the ranges (materials_fields).
  table.lithology = {{-3, "quote \" backslash \\ tab \t newline \n end", 2.0e9 / 3.0, (0.1 + 0.2) * 1e5, 1e2,
                      1e13, 0.0, 0.1 + 0.7, 1.0, 5e-324, 1.23456789125},
                     {2147483647, "Gneiß, éboulis", 3e8, 2e6, 2.9e8, 3.1e8, 0.7, 0.45, 0.25, 0.5, 0.1}};
  table.vegetation = {{-2147483647 - 1, "", 0.0}, {7, "aulnaie", 0.012345678901234567}};
  table.default_lithology = 2147483647;
  table.default_vegetation = 7;
  const auto path = write_file("materials_awkward_round_trip", materials_to_toml(table));
  expect_same(read_materials(path), table);
}

TEST(MaterialsFile, DocumentedDefaultFileIsTheBuiltinTable) {
  expect_same(read_materials(test::source_dir() / "docs" / "materials-default.toml"), builtin_materials());
}

TEST(MaterialsFile, WrittenNumbersAreTomlFloatsWithUnits) {
  const std::string text = materials_to_toml(builtin_materials());
  EXPECT_NE(text.find("elastic_slope = 1.0e8"), std::string::npos) << text;
  EXPECT_NE(text.find("# k1, Pa/m"), std::string::npos);
  EXPECT_NE(text.find("restitution_normal = 0.0 "), std::string::npos);
  EXPECT_NE(text.find("deperdition = 0.015 "), std::string::npos);
  EXPECT_NE(text.find("[[vegetation]]"), std::string::npos);
}

// A small valid file; each error case below changes one piece of it.
const std::string valid_file = R"(default_lithology = 4
default_vegetation = 0

[[lithology]]
code = 4
name = "talus"
elastic_slope = 1.0e8
yield_pressure = 8.0e5
plastic_slope = 7.0e7
unloading_slope = 1.9e8
friction = 0.78
rolling_friction = 0.4
restitution_normal = 0.38
restitution_tangential = 0.65
noise_amplitude = 0.3

[[lithology]]
code = 6
name = "bedrock"
elastic_slope = 5.0e9
yield_pressure = 2.0e7
plastic_slope = 3.5e9
unloading_slope = 6.0e9
friction = 0.58
rolling_friction = 0.3
restitution_normal = 0.53
restitution_tangential = 0.75
noise_amplitude = 0.2

[[vegetation]]
code = 0
name = "bare"
deperdition = 0.0

[[vegetation]]
code = 3
name = "open forest"
deperdition = 0.007
)";

TEST(MaterialsFile, SmallValidFileReads) {
  const MaterialsTable table = read_materials(write_file("materials_small_valid", valid_file));
  ASSERT_EQ(table.lithology.size(), 2u);
  ASSERT_EQ(table.vegetation.size(), 2u);
  EXPECT_EQ(table.find_lithology(6)->yield_pressure, 2.0e7);
  EXPECT_EQ(table.find_vegetation(3)->name, "open forest");
  EXPECT_EQ(table.default_lithology, 4);
}

TEST(MaterialsFile, IntegersAreAcceptedWhereNumbersAreExpected) {
  std::string text = valid_file;
  text.replace(text.find("friction = 0.78"), 15, "friction = 1");
  EXPECT_EQ(read_materials(write_file("materials_integer_number", text)).find_lithology(4)->friction, 1.0);
}

// One bad input: `from` in the valid file becomes `to` (from empty: `to` is the whole file).
struct BadInput {
  std::string name;
  std::string from;
  std::string to;
  std::vector<std::string> expected;  // fragments of the message
};

void PrintTo(const BadInput& input, std::ostream* out) { *out << input.name; }

class MaterialsFileError : public ::testing::TestWithParam<BadInput> {};

TEST_P(MaterialsFileError, ThrowsOneLineNamingFileAndProblem) {
  const BadInput& input = GetParam();
  std::string text = input.to;
  if (!input.from.empty()) {
    text = valid_file;
    const auto at = text.find(input.from);
    ASSERT_NE(at, std::string::npos) << input.from;
    text.replace(at, input.from.size(), input.to);
  }
  const auto path = write_file("materials_error_" + input.name, text);
  try {
    read_materials(path);
    FAIL() << "no error for " << input.name;
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(path.string() + " (materials): "), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    for (const std::string& fragment : input.expected) {
      EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << message;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(
    BadInputs, MaterialsFileError,
    ::testing::Values(
        BadInput{"syntax", "name = \"bedrock\"", "name = \"bedrock", {"TOML syntax error at line 19"}},
        BadInput{"missing_field", "yield_pressure = 2.0e7\n", "",
                 {"missing field 'yield_pressure'", "lithology class 6"}},
        BadInput{"missing_code", "code = 6\n", "", {"missing field 'code'", "lithology entry 2"}},
        BadInput{"missing_name", "name = \"open forest\"\n", "", {"missing field 'name'", "vegetation class 3"}},
        BadInput{"missing_deperdition", "deperdition = 0.007\n", "",
                 {"missing field 'deperdition'", "vegetation class 3"}},
        BadInput{"missing_default", "default_vegetation = 0\n", "", {"missing field 'default_vegetation'"}},
        BadInput{"no_vegetation", "[[vegetation]]\ncode = 0\nname = \"bare\"\ndeperdition = 0.0\n\n"
                                  "[[vegetation]]\ncode = 3\nname = \"open forest\"\ndeperdition = 0.007\n",
                 "", {"no [[vegetation]] classes"}},
        BadInput{"number_type", "friction = 0.78", "friction = \"high\"",
                 {"'friction' in lithology class 4 must be a number (found: string)", "line 11"}},
        BadInput{"code_type", "code = 6", "code = 6.0", {"'code' in lithology entry 2 must be an integer"}},
        BadInput{"name_type", "name = \"bare\"", "name = 0", {"'name' in vegetation class 0 must be a string"}},
        BadInput{"default_type", "default_lithology = 4", "default_lithology = \"talus\"",
                 {"'default_lithology' must be an integer"}},
        BadInput{"classes_type", "", "default_lithology = 4\ndefault_vegetation = 0\nlithology = 3\n",
                 {"'lithology' must be a list of [[lithology]] tables (found: integer)"}},
        BadInput{"not_finite", "noise_amplitude = 0.3", "noise_amplitude = inf",
                 {"'noise_amplitude' in lithology class 4 must be finite"}},
        BadInput{"plastic_above_elastic", "plastic_slope = 7.0e7", "plastic_slope = 2.0e8",
                 {"lithology class 4", "0 < plastic_slope < elastic_slope < unloading_slope"}},
        BadInput{"unloading_below_elastic", "unloading_slope = 6.0e9", "unloading_slope = 4.0e9",
                 {"lithology class 6", "0 < plastic_slope < elastic_slope < unloading_slope"}},
        BadInput{"negative_plastic", "plastic_slope = 7.0e7", "plastic_slope = -7.0e7",
                 {"'plastic_slope' in lithology class 4 = -7.0e7", "expected 100.0 to 1.0e12 Pa/m"}},
        BadInput{"yield", "yield_pressure = 8.0e5", "yield_pressure = 0",
                 {"'yield_pressure' in lithology class 4 = 0.0", "expected 100.0 to 1.0e10 Pa"}},
        BadInput{"friction", "friction = 0.58", "friction = -0.3", {"'friction' in lithology class 6 = -0.3", "expected 0.0 to 10.0"}},
        BadInput{"rolling_friction", "rolling_friction = 0.3", "rolling_friction = -0.1",
                 {"'rolling_friction' in lithology class 6 = -0.1", "expected 0.0 to 10.0"}},
        BadInput{"restitution_normal", "restitution_normal = 0.38", "restitution_normal = 1.2",
                 {"'restitution_normal' in lithology class 4 = 1.2", "expected 0.0 to 1.0"}},
        BadInput{"restitution_tangential", "restitution_tangential = 0.75", "restitution_tangential = -0.1",
                 {"'restitution_tangential' in lithology class 6 = -0.1", "expected 0.0 to 1.0"}},
        BadInput{"noise", "noise_amplitude = 0.2", "noise_amplitude = -0.2",
                 {"'noise_amplitude' in lithology class 6 = -0.2", "expected 0.0 to 10.0 m"}},
        BadInput{"deperdition", "deperdition = 0.007", "deperdition = -0.007",
                 {"'deperdition' in vegetation class 3 = -0.007", "expected 0.0 to 10.0 1/m"}},
        BadInput{"huge_elastic", "elastic_slope = 1.0e8", "elastic_slope = 1.0e300",
                 {"'elastic_slope' in lithology class 4 = 1.0e300", "expected 1000.0 to 1.0e12 Pa/m"}},
        BadInput{"huge_friction", "friction = 0.58", "friction = 1.0e6", {"'friction' in lithology class 6 = 1.0e6"}},
        BadInput{"huge_deperdition", "deperdition = 0.007", "deperdition = 5.0e3",
                 {"'deperdition' in vegetation class 3 = 5000.0", "expected 0.0 to 10.0 1/m"}},
        BadInput{"duplicate_lithology", "code = 6", "code = 4", {"duplicate lithology code 4"}},
        BadInput{"duplicate_vegetation", "code = 3", "code = 0", {"duplicate vegetation code 0"}},
        BadInput{"default_lithology_absent", "default_lithology = 4", "default_lithology = 5",
                 {"default_lithology = 5 is not one of the [[lithology]] classes"}},
        BadInput{"default_vegetation_absent", "default_vegetation = 0", "default_vegetation = 4",
                 {"default_vegetation = 4 is not one of the [[vegetation]] classes"}},
        BadInput{"unknown_class_key", "friction = 0.58", "frction = 0.58",
                 {"unknown key 'frction'", "lithology entry 2", "line 24"}},
        BadInput{"unknown_top_key", "default_vegetation = 0", "default_vegetation = 0\ndefault_lithologie = 4",
                 {"unknown key 'default_lithologie' at the top level"}}),
    [](const ::testing::TestParamInfo<BadInput>& param_info) { return param_info.param.name; });

TEST(MaterialsFile, MissingFileIsReported) {
  const auto path = test::fresh_folder("materials_missing") / "nowhere.toml";
  try {
    read_materials(path);
    FAIL() << "no error for a missing file";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), path.string() + " (materials): materials file not found");
  }
}

}  // namespace
}  // namespace talus::gis
