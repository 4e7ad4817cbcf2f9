// run.json (docs/architecture.md section 3): valid JSON with the expected keys, inputs described with their
// size, CRS and a SHA-256 checksum that agrees with sha256sum.
#include "talus/gis/run_record.hpp"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <memory>
#include <regex>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster_fixtures.hpp"
#include "talus/gis/build_commit.hpp"
#include "test_paths.hpp"

namespace talus::gis {
namespace {

namespace fs = std::filesystem;
using ordered_json = nlohmann::ordered_json;

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// The checksum coreutils' sha256sum gives for a file.
std::string sha256sum(const fs::path& path) {
  const std::string command = "sha256sum '" + path.string() + "'";
  std::unique_ptr<FILE, int (*)(FILE*)> pipe(popen(command.c_str(), "r"), pclose);
  if (!pipe) return "popen failed";
  char digest[65] = {};
  return std::fread(digest, 1, 64, pipe.get()) == 64 ? std::string(digest) : "no output from sha256sum";
}

ordered_json read_json(const fs::path& path) {
  std::ifstream in(path);
  return ordered_json::parse(in);  // throws on anything that is not JSON
}

TEST(RunRecord, ChecksumsAreSha256OfTheFileBytes) {
  const auto folder = test::fresh_folder("run_record_sha256");
  write_text(folder / "abc.txt", "abc");
  write_text(folder / "empty.txt", "");
  // FIPS 180-2 test vectors.
  EXPECT_EQ(sha256_of_file(folder / "abc.txt"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_of_file(folder / "empty.txt"), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");

  // Larger than the read buffer and not a multiple of the 64-byte block.
  std::string text;
  for (long i = 0; text.size() < 3'500'000; ++i) text += "line " + std::to_string(i * 7919 % 100003) + "\n";
  write_text(folder / "large.txt", text);
  EXPECT_EQ(sha256_of_file(folder / "large.txt"), sha256sum(folder / "large.txt"));
  EXPECT_EQ(sha256_of_file(folder / "abc.txt"), sha256sum(folder / "abc.txt"));
  EXPECT_THROW(sha256_of_file(folder / "missing.txt"), std::runtime_error);
}

TEST(RunRecord, WritesValidJsonWithTheExpectedKeysInOrder) {
  const auto folder = test::fresh_folder("run_record_keys");
  RunRecord record;
  record.set_command_line({"talus", "rockfall", "--dem", "dem.tif", "--runs", "10"});
  record.set_parameters(nlohmann::json{{"run", {{"runs", 10}, {"seed", 42}}}});
  record.set("seed", 42);
  record.set("counts", {{"sources", 3}, {"trajectories", 30}});
  record.set("seed", 43);  // replaces
  record.add_timing("read_inputs", 0.25);
  record.add_timing("simulate", 1.5);
  record.add_timing("read_inputs", 0.5);
  record.write(folder / "run.json");

  const auto run = read_json(folder / "run.json");
  std::vector<std::string> keys;
  for (const auto& item : run.items()) keys.push_back(item.key());
  EXPECT_EQ(keys, (std::vector<std::string>{"software", "version", "git_commit", "gdal_version", "started_utc",
                                            "finished_utc", "host", "command_line", "inputs", "parameters", "seed",
                                            "counts", "timings_s"}));
  EXPECT_EQ(run["software"], "talus");
  EXPECT_EQ(run["version"], TALUS_VERSION);
  // 40 hexadecimal digits and "-modified" when the build's tracked files differed, or "unknown".
  EXPECT_TRUE(std::regex_match(run["git_commit"].get<std::string>(), std::regex("[0-9a-f]{40}(-modified)?|unknown")))
      << run["git_commit"];
  EXPECT_EQ(run["git_commit"].get<std::string>(), std::string(git_commit()));
  EXPECT_FALSE(run["gdal_version"].get<std::string>().empty());
  const std::regex utc(R"(\d{4}-\d\d-\d\dT\d\d:\d\d:\d\dZ)");
  EXPECT_TRUE(std::regex_match(run["started_utc"].get<std::string>(), utc)) << run["started_utc"];
  EXPECT_TRUE(std::regex_match(run["finished_utc"].get<std::string>(), utc)) << run["finished_utc"];
  EXPECT_LE(run["started_utc"].get<std::string>(), run["finished_utc"].get<std::string>());
  EXPECT_GE(run["host"]["hardware_threads"].get<int>(), 1);
  EXPECT_EQ(run["command_line"], (ordered_json{"talus", "rockfall", "--dem", "dem.tif", "--runs", "10"}));
  EXPECT_TRUE(run["inputs"].is_object());
  EXPECT_TRUE(run["inputs"].empty());
  EXPECT_EQ(run["parameters"]["run"]["runs"], 10);
  EXPECT_EQ(run["seed"], 43);
  EXPECT_EQ(run["counts"]["trajectories"], 30);
  EXPECT_EQ(run["timings_s"]["read_inputs"], 0.75);
  EXPECT_EQ(run["timings_s"]["simulate"], 1.5);
}

TEST(RunRecord, DescribesRasterVectorAndOtherInputsWithTheirChecksum) {
  const auto folder = test::fresh_folder("run_record_inputs");
  test::RasterFixture fixture;
  fixture.width = 12;
  fixture.height = 7;
  fixture.crs = "EPSG:31287";
  test::write_raster(folder / "dem.tif", fixture);
  test::write_vector(folder / "release.gpkg", "EPSG:31287", {{"POINT (500015 5199985)", 1.0}, {"POINT (500025 5199975)", 2.0}},
                     true);
  const std::string materials_text = "[default]\nname = \"rock\"\n";
  write_text(folder / "materials.toml", materials_text);

  GridSpec used;  // the grid the run used for the lithology, say after --crs
  used.width = 40;
  used.height = 30;
  RunRecord record;
  record.add_input("dem", folder / "dem.tif", nullptr);
  record.add_input("lithology", folder / "dem.tif", &used);
  record.add_input("release", folder / "release.gpkg", nullptr);
  record.add_input("materials", folder / "materials.toml", nullptr);
  record.write(folder / "run.json");
  const auto inputs = read_json(folder / "run.json")["inputs"];

  const auto& dem = inputs["dem"];
  EXPECT_EQ(dem["path"], (folder / "dem.tif").string());
  EXPECT_EQ(dem["bytes"], fs::file_size(folder / "dem.tif"));
  EXPECT_EQ(dem["sha256"], sha256sum(folder / "dem.tif"));
  EXPECT_EQ(dem["columns"], 12);
  EXPECT_EQ(dem["rows"], 7);
  EXPECT_NE(dem["crs"].get<std::string>().find("EPSG:31287"), std::string::npos) << dem["crs"];

  EXPECT_EQ(inputs["lithology"]["columns"], 40);
  EXPECT_EQ(inputs["lithology"]["rows"], 30);
  EXPECT_EQ(inputs["lithology"]["crs"], "local (no CRS)");
  EXPECT_EQ(inputs["lithology"]["sha256"], dem["sha256"]);

  const auto& release = inputs["release"];
  EXPECT_EQ(release["sha256"], sha256sum(folder / "release.gpkg"));
  EXPECT_EQ(release["features"], 2);
  EXPECT_TRUE(release["layer"].is_string());
  EXPECT_NE(release["crs"].get<std::string>().find("EPSG:31287"), std::string::npos) << release["crs"];

  const auto& materials = inputs["materials"];
  EXPECT_EQ(materials["bytes"], materials_text.size());
  EXPECT_EQ(materials["sha256"], sha256sum(folder / "materials.toml"));
  EXPECT_FALSE(materials.contains("columns"));
  EXPECT_FALSE(materials.contains("crs"));
}

TEST(RunRecord, RelativePathsAreRecordedAbsolute) {
  const auto folder = test::fresh_folder("run_record_relative");
  write_text(folder / "scenario.toml", "[run]\nruns = 5\n");
  const auto previous = fs::current_path();
  fs::current_path(folder);
  RunRecord record;
  record.add_input("scenario", "./scenario.toml", nullptr);
  fs::current_path(previous);
  EXPECT_EQ(record.to_json()["inputs"]["scenario"]["path"], (folder / "scenario.toml").string());
}

TEST(RunRecord, RefusesMisuseAndNamesFilesItCannotReadOrWrite) {
  const auto folder = test::fresh_folder("run_record_errors");
  write_text(folder / "a.toml", "x = 1\n");
  RunRecord record;
  record.add_input("materials", folder / "a.toml", nullptr);
  EXPECT_THROW(record.add_input("materials", folder / "a.toml", nullptr), std::logic_error);
  EXPECT_THROW(record.set("inputs", 1), std::logic_error);
  EXPECT_THROW(record.set("timings_s", 1), std::logic_error);
  const auto missing = folder / "missing.tif";
  try {
    record.add_input("dem", missing, nullptr);
    ADD_FAILURE() << "no error for a missing input";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(missing.string()), std::string::npos) << error.what();
  }
  const auto unwritable = folder / "no_such_folder" / "run.json";
  try {
    record.write(unwritable);
    ADD_FAILURE() << "no error for an unwritable path";
  } catch (const std::runtime_error& error) {
    EXPECT_NE(std::string(error.what()).find(unwritable.string()), std::string::npos) << error.what();
  }
}

TEST(RunRecord, WritesInvalidUtf8AsReplacementCharacters) {
  const auto folder = test::fresh_folder("run_record_utf8");
  RunRecord record;
  record.set_command_line({"talus", "--out", "caf\xe9"});  // Latin-1, as an old shell might pass it
  record.write(folder / "run.json");
  EXPECT_EQ(read_json(folder / "run.json")["command_line"][2], "caf\xef\xbf\xbd");
}

}  // namespace
}  // namespace talus::gis
