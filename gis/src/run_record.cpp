// RunRecord: run.json assembled with nlohmann::json in a fixed, readable order; input files
// probed through GDAL and checksummed with GDAL's SHA-256. docs/layers.md describes the fields.
#include "talus/gis/run_record.hpp"

#include <cpl_port.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <ctime>
#include <fstream>
#include <stdexcept>
#include <system_error>
#include <thread>
#include <string>
#include <utility>
#include <vector>

#include "talus/gis/build_commit.hpp"
#include "talus/gis/dem_reader.hpp"
#include "talus/gis/gdal_dataset.hpp"

// GDAL exports its SHA-256 but does not install port/cpl_sha256.h; these are that header's
// declarations (GDAL 3.6), whose context layout has not changed since the header appeared.
extern "C" {
struct CPL_SHA256Context {
  GUIntBig totalLength;
  GUInt32 hash[8];
  GUInt32 bufferLength;
  union {
    GUInt32 words[16];
    GByte bytes[64];
  } buffer;
};
void CPL_SHA256Init(CPL_SHA256Context* sc);
void CPL_SHA256Update(CPL_SHA256Context* sc, const void* data, size_t len);
void CPL_SHA256Final(CPL_SHA256Context* sc, GByte hash[32]);
}

namespace talus::gis {
namespace {

using ordered_json = nlohmann::ordered_json;

// The keys RunRecord fills itself (to_json).
constexpr std::array kRecordKeys{"software", "version", "git_commit", "gdal_version", "started_utc", "finished_utc",
                                 "host", "command_line", "inputs", "parameters", "timings_s"};

// "2024-05-17T09:41:03Z"
std::string utc_now() {
  const std::time_t now = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm utc{};
  gmtime_r(&now, &utc);
  std::array<char, 32> text{};
  std::strftime(text.data(), text.size(), "%Y-%m-%dT%H:%M:%SZ", &utc);
  return text.data();
}

// Columns, rows and CRS of a raster, or first layer, feature count and CRS of a vector file, as
// GDAL reads them; nothing for a file GDAL does not open (a TOML file, say).
void describe_file(const std::filesystem::path& path, ordered_json& entry) {
  ensure_gdal_ready();
  GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!dataset) return;
  if (dataset->GetRasterCount() > 0) {
    entry["columns"] = dataset->GetRasterXSize();
    entry["rows"] = dataset->GetRasterYSize();
    entry["crs"] = crs_display_name(wkt_of(dataset->GetSpatialRef()));
  } else if (dataset->GetLayerCount() > 0) {
    OGRLayer* layer = dataset->GetLayer(0);
    entry["layer"] = layer->GetName();
    entry["features"] = layer->GetFeatureCount();
    entry["crs"] = crs_display_name(wkt_of(layer->GetSpatialRef()));
  }
}

// JSON text indented by two spaces per level, as dump(2) writes it, except that an array of
// numbers stays on one line (run.json's runs per source: one line for thousands of sources).
// Invalid UTF-8 (a path in a legacy encoding) becomes U+FFFD rather than failing the run.
void write_json(std::string& text, const ordered_json& value, int depth) {
  const auto scalar = [](const ordered_json& v) { return v.dump(-1, ' ', false, ordered_json::error_handler_t::replace); };
  const bool numbers = value.is_array() && std::all_of(value.begin(), value.end(), [](const ordered_json& v) { return v.is_number(); });
  if (!value.is_structured() || value.empty() || numbers) {
    text += scalar(value);
    return;
  }
  const std::string inner(2 * (depth + 1), ' ');
  text += value.is_object() ? "{\n" : "[\n";
  bool first = true;
  for (auto it = value.begin(); it != value.end(); ++it) {
    text += (first ? "" : ",\n") + inner;
    first = false;
    if (value.is_object()) text += scalar(ordered_json(it.key())) + ": ";
    write_json(text, *it, depth + 1);
  }
  text += "\n" + std::string(2 * depth, ' ') + (value.is_object() ? "}" : "]");
}

}  // namespace

std::string sha256_of_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path.string() + " for its checksum");
  CPL_SHA256Context context;
  CPL_SHA256Init(&context);
  std::vector<char> chunk(1 << 20);
  while (in) {
    in.read(chunk.data(), static_cast<std::streamsize>(chunk.size()));
    CPL_SHA256Update(&context, chunk.data(), static_cast<std::size_t>(in.gcount()));
  }
  if (in.bad()) throw std::runtime_error("cannot read " + path.string() + " for its checksum");
  std::array<GByte, 32> digest{};
  CPL_SHA256Final(&context, digest.data());
  std::string hex;
  for (const GByte byte : digest) {
    std::array<char, 3> pair{};
    std::snprintf(pair.data(), pair.size(), "%02x", static_cast<unsigned>(byte));
    hex += pair.data();
  }
  return hex;
}

RunRecord::RunRecord() : started_utc_(utc_now()) {}

void RunRecord::set_command_line(const std::vector<std::string>& arguments) { command_line_ = arguments; }

void RunRecord::add_input(const std::string& role, const std::filesystem::path& path, const GridSpec* grid) {
  if (inputs_.contains(role)) throw std::logic_error("run.json already has an input " + role);
  std::error_code error;
  const bool regular = std::filesystem::is_regular_file(path, error);
  if (!regular && !std::filesystem::exists(path, error))
    throw std::runtime_error("cannot record " + describe_input(path, role) + " in run.json: file not found");
  ordered_json entry;
  entry["path"] = std::filesystem::absolute(path).lexically_normal().string();
  if (regular) {  // a folder (a File Geodatabase, say) has neither
    entry["bytes"] = std::filesystem::file_size(path);
    entry["sha256"] = sha256_of_file(path);
  }
  if (grid != nullptr) {
    entry["columns"] = grid->width;
    entry["rows"] = grid->height;
    entry["crs"] = crs_display_name(grid->crs_wkt);
  } else {
    describe_file(path, entry);
  }
  inputs_[role] = std::move(entry);
}

void RunRecord::set_parameters(ordered_json parameters) { parameters_ = std::move(parameters); }

void RunRecord::set(const std::string& key, ordered_json value) {
  for (const char* reserved : kRecordKeys)
    if (key == reserved) throw std::logic_error("run.json fills " + key + " itself");
  items_[key] = std::move(value);
}

void RunRecord::add_timing(const std::string& phase, double seconds) {
  timings_[phase] = timings_.value(phase, 0.0) + seconds;
}

ordered_json RunRecord::to_json() const {
  ordered_json record;
  record["software"] = "talus";
  record["version"] = TALUS_VERSION;
  record["git_commit"] = git_commit();
  record["gdal_version"] = GDALVersionInfo("RELEASE_NAME");
  record["started_utc"] = started_utc_;
  record["finished_utc"] = utc_now();
  record["host"] = {{"hardware_threads", std::thread::hardware_concurrency()}};
  record["command_line"] = command_line_;
  record["inputs"] = inputs_;
  record["parameters"] = parameters_;
  for (const auto& [key, value] : items_.items()) record[key] = value;
  record["timings_s"] = timings_;
  return record;
}

void RunRecord::write(const std::filesystem::path& path) const {
  std::string text;
  write_json(text, to_json(), 0);
  text += "\n";
  std::ofstream out(path, std::ios::binary);
  out.write(text.data(), static_cast<std::streamsize>(text.size()));
  out.close();
  if (!out) throw std::runtime_error("cannot write " + path.string());
}

}  // namespace talus::gis
