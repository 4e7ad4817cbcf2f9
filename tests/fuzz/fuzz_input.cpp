// The shared pieces of the fuzz targets (fuzz_input.hpp).
#include "fuzz_input.hpp"

#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <stdlib.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <vector>

#include "talus/gis/gdal_dataset.hpp"

namespace talus::fuzz {

FuzzFolder::FuzzFolder() {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/talus-fuzz-XXXXXX";
  if (::mkdtemp(pattern.data()) == nullptr) {
    std::perror("talus fuzz: mkdtemp");
    std::abort();
  }
  path_ = pattern;
}

FuzzFolder::~FuzzFolder() {
  std::error_code ec;
  std::filesystem::remove_all(path_, ec);
}

std::filesystem::path FuzzFolder::write(const std::string& name, std::string_view bytes) const {
  const std::filesystem::path file = path_ / name;
  std::ofstream out(file, std::ios::binary | std::ios::trunc);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  if (!out) {
    std::fprintf(stderr, "talus fuzz: cannot write %s\n", file.c_str());
    std::abort();
  }
  return file;
}

const FuzzFolder& fuzz_folder() {
  static const FuzzFolder folder;
  return folder;
}

void prepare_gdal() {
  CPLSetConfigOption("GDAL_DISABLE_READDIR_ON_OPEN", "EMPTY_DIR");
  CPLSetConfigOption("GDAL_CACHEMAX", "64");
  CPLSetConfigOption("CPL_DEBUG", "OFF");
  gis::ensure_gdal_ready();
}

const std::filesystem::path& fixed_dem() {
  static const std::filesystem::path path = [] {
    prepare_gdal();
    const std::filesystem::path file = fuzz_folder().path() / "dem.tif";
    constexpr int n = 16;
    GDALDriver* gtiff = GetGDALDriverManager()->GetDriverByName("GTiff");
    GDALDatasetUniquePtr dem(gtiff->Create(file.c_str(), n, n, 1, GDT_Float32, nullptr));
    double geotransform[6] = {600000.0, 10.0, 0.0, 5200160.0, 0.0, -10.0};
    dem->SetGeoTransform(geotransform);
    OGRSpatialReference utm;
    utm.importFromEPSG(32632);
    dem->SetSpatialRef(&utm);
    std::vector<float> elevations(n * n);
    for (int row = 0; row < n; ++row) {
      for (int col = 0; col < n; ++col) elevations[row * n + col] = static_cast<float>(1500.0 - 4.0 * col - 6.0 * row);
    }
    if (dem->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, n, n, elevations.data(), n, n, GDT_Float32, 0, 0) != CE_None) {
      std::fprintf(stderr, "talus fuzz: cannot write %s\n", file.c_str());
      std::abort();
    }
    return file;
  }();
  return path;
}

bool small_enough(const std::filesystem::path& path) {
  prepare_gdal();
  GDALDatasetUniquePtr dataset(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!dataset) return true;  // the readers refuse it themselves
  const double cells = static_cast<double>(dataset->GetRasterXSize()) * dataset->GetRasterYSize();
  return cells <= kMaxInputCells && dataset->GetRasterCount() <= kMaxInputBands;
}

std::optional<std::filesystem::path> gdal_input(const std::string& name, const std::uint8_t* data, std::size_t size) {
  std::filesystem::path path = fuzz_folder().write(name, data, size);
  if (!small_enough(path)) return std::nullopt;
  return path;
}

}  // namespace talus::fuzz
