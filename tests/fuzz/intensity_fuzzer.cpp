// Fuzz target: intensity guideline TOML files (--intensity FILE.toml, docs/hazard-statistics.md,
// "Intensity classes"): the guideline read for rock fall and for mud flow, its QGIS style, and its
// classes applied to small layers of every name its thresholds use; its hazard matrix
// (docs/study.md, "Hazard map") with its style, applied to the classified layers.
#include <cstddef>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>

#include "fuzz_input.hpp"
#include "intensity_guidelines.hpp"
#include "talus/gis/hazard_zones_writer.hpp"
#include "talus/gis/intensity_style.hpp"
#include "talus/hazard/hazard_matrix.hpp"

namespace {

// Classifies a 2 x 2 grid whose cells run from nothing to far above any threshold.
talus::Grid<float> classify_small_layers(const talus::IntensityScheme& scheme) {
  talus::GridSpec spec;
  spec.width = 2;
  spec.height = 2;
  spec.geotransform = {0.0, 10.0, 0.0, 20.0, 0.0, -10.0};
  const talus::Grid<float> values(spec, {0.0f, 1.0f, 350.0f, 1e6f});
  std::map<std::string, const talus::Grid<float>*> layers;
  for (const auto& c : scheme.classes) {
    for (const auto& alternative : c.when) {
      for (const auto& threshold : alternative) {
        for (const auto& layer : threshold.layers) layers[layer] = &values;
      }
    }
  }
  return talus::classify_intensity(scheme, layers);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = talus::fuzz::fuzz_folder().write("guideline.toml", data, size);
  for (const char* process : {"rockfall", "mudflow"}) {
    talus::fuzz::refused_or_read([&] {
      const talus::IntensityScheme scheme = talus::cli::intensity_scheme(path.string(), process);
      talus::gis::intensity_style_qml(scheme);
      const talus::Grid<float> intensity = classify_small_layers(scheme);
      if (const auto matrix = talus::cli::hazard_matrix(path.string())) {
        talus::gis::hazard_style_qml(*matrix);
        talus::Grid<float> hazard(intensity.spec(), 0.0f);
        for (const double years : {1.0, 30.0, 1e6}) {
          try {
            talus::raise_hazard(hazard, *matrix, scheme, intensity, years);
          } catch (const std::invalid_argument&) {  // a class without a row: talus study refuses it first
          }
        }
      }
    });
  }
  return 0;
}
