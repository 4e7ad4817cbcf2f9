// Fuzz target: study files (`talus study F.toml`, docs/study.md): the TOML parse, the sections and
// keys of [inputs], [hazard] and every scenario, names, return periods and source keys, as
// read_study checks them before any scenario's parameters.
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "study_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = talus::fuzz::fuzz_folder().write("study.toml", data, size);
  talus::fuzz::refused_or_read([&] { talus::cli::read_study(path); });
  return 0;
}
