// Units of work committed one by one (unit_parts.hpp; issue 19, item 5).
#include "unit_parts.hpp"

#include <fstream>
#include <iterator>
#include <sstream>

#include "talus/core/errors.hpp"

namespace talus::cli {
namespace {

std::string file_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The bytes written to `path` whole or not at all: a temporary file beside it, renamed.
void write_whole(const std::filesystem::path& path, const char* data, std::size_t size) {
  const std::filesystem::path partial = path.string() + ".partial";
  {
    std::ofstream out(partial, std::ios::binary | std::ios::trunc);
    out.write(data, static_cast<std::streamsize>(size));
    if (!out) throw InputError(partial.string() + ": cannot write a unit of work (is the disk full?)");
  }
  std::filesystem::rename(partial, path);
}

}  // namespace

void UnitParts::prepare(const std::string& key) const {
  const std::filesystem::path key_file = folder_ / "key.json";
  if (std::filesystem::exists(key_file) && file_text(key_file) == key) return;
  std::filesystem::remove_all(folder_);
  std::filesystem::create_directories(folder_);
  write_whole(key_file, key.data(), key.size());
}

std::filesystem::path UnitParts::file(std::size_t tile, std::size_t chunk) const {
  return folder_ / ("tile-" + std::to_string(tile) + "-chunk-" + std::to_string(chunk) + "-rank-" +
                    std::to_string(rank_) + "-of-" + std::to_string(ranks_) + ".bin");
}

std::optional<std::vector<std::uint8_t>> UnitParts::load(std::size_t tile, std::size_t chunk) const {
  std::ifstream in(file(tile, chunk), std::ios::binary);
  if (!in) return std::nullopt;
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void UnitParts::commit(std::size_t tile, std::size_t chunk, const std::vector<std::uint8_t>& bytes) const {
  write_whole(file(tile, chunk), reinterpret_cast<const char*>(bytes.data()), bytes.size());
}

}  // namespace talus::cli
