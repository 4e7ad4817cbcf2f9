// What a rock-fall or mud-flow run chose besides its numbers (rockfall_parameters.hpp,
// mudflow_parameters.hpp): the intensity classes and whether it writes a QGIS project.
#pragma once

#include <optional>

#include "talus/hazard/intensity_classes.hpp"

namespace talus::cli {

struct RunChoices {
  std::optional<IntensityScheme> intensity;  // none: no intensity.tif
  bool project = true;                       // project.qgz, hillshade.tif and quicklook/*.png
};

}  // namespace talus::cli
