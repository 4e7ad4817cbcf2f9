// Fuzz target: scenario TOML files (--scenario), read and checked as `talus rockfall` and
// `talus mudflow` do before any work: the scenario's sections onto the parameter table, the
// material preset, the flags' own checks, every range and the intensity guideline it names
// (docs/fuzzing.md).
#include <cstddef>
#include <cstdint>

#include "fuzz_input.hpp"
#include "mudflow_parameters.hpp"
#include "rockfall_parameters.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto scenario = talus::fuzz::fuzz_folder().write("scenario.toml", data, size);
  talus::fuzz::refused_or_read([&] { talus::cli::check_rockfall_scenario(scenario); });
  talus::fuzz::refused_or_read([&] { talus::cli::check_mudflow_scenario(scenario); });
  return 0;
}
