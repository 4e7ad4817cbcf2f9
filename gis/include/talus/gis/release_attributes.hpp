// The rock-fall attributes of a release feature (issue 16; docs/inputs.md, "Rock-fall
// attributes"): `shape`, `block_size`, `density` or `mass`, `vx`, `vy`, `vz` and
// `release_height`, read through OGR into the feature's release conditions.
#pragma once

#include <ogr_feature.h>

#include <string>

#include "talus/core/release_conditions.hpp"
#include "talus/rockfall/rock.hpp"

namespace talus::gis {

// The conditions a feature's attributes give, fields matched case-insensitively; a missing
// field, a NULL value or a blank text keeps the run's value. `run_rock` is the run's rock: a
// mass is divided by the volume of the feature's rock, which takes its shape and axes from the
// run where the feature gives none. Throws InputError "WHERE: FIELD VALUE: PROBLEM" naming the
// allowed range, `where` naming the file and the feature.
ReleaseConditions read_release_conditions(const OGRFeature& feature, const Rock& run_rock, const std::string& where);

}  // namespace talus::gis
