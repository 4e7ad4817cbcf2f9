// What the fuzz targets share (docs/fuzzing.md): a private folder that each input is written
// into as the file a user would give, the fixed DEM the secondary inputs are read onto, and the
// rule that a refused input is a normal outcome.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

#include "talus/core/errors.hpp"

namespace talus::fuzz {

// A folder of the process's own under $TMPDIR (or /tmp), removed at exit. The readers take
// paths, as the program does, so every input goes through a real file.
class FuzzFolder {
 public:
  FuzzFolder();
  ~FuzzFolder();
  FuzzFolder(const FuzzFolder&) = delete;
  FuzzFolder& operator=(const FuzzFolder&) = delete;

  // Writes `bytes` to the file `name` in the folder (replacing it) and returns its path.
  std::filesystem::path write(const std::string& name, std::string_view bytes) const;
  std::filesystem::path write(const std::string& name, const std::uint8_t* data, std::size_t size) const {
    return write(name, std::string_view(reinterpret_cast<const char*>(data), size));
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

// The folder of this process's inputs, made on first use.
const FuzzFolder& fuzz_folder();

// GDAL set up once for fuzzing: drivers registered, messages quiet, no directory listing on
// open (no sidecar files are looked for) and a small block cache.
void prepare_gdal();

// A 16 x 16 DEM of 10 m cells in WGS 84 / UTM zone 32N, a plane sloping to the south-east,
// written once into fuzz_folder() as dem.tif: the grid the lithology, vegetation, erodible and
// release inputs are aligned onto.
const std::filesystem::path& fixed_dem();

// Whether GDAL's view of the file is small enough to read here: at most kMaxInputCells cells
// per band and kMaxInputBands bands. The readers themselves accept any grid that fits in the
// machine's memory; the fuzz targets skip larger ones, which a few bytes of header can declare,
// so that one input does not read gigabytes of nothing (GDAL's own fuzzers do the same).
inline constexpr double kMaxInputCells = 1 << 18;
inline constexpr int kMaxInputBands = 16;
bool small_enough(const std::filesystem::path& path);
// A GDAL input written to `name` in fuzz_folder(), or nothing when it is not small_enough.
std::optional<std::filesystem::path> gdal_input(const std::string& name, const std::uint8_t* data, std::size_t size);

// Runs `read`: a refused input (InputError, the program's exit code 2) is a normal outcome.
// Every other exception escapes and ends the fuzzer as a finding, as do crashes, sanitizer
// reports, leaks, timeouts and allocations beyond -malloc_limit_mb.
template <class Read>
void refused_or_read(Read&& read) {
  try {
    read();
  } catch (const InputError&) {
  }
}

}  // namespace talus::fuzz
