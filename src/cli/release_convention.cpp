#include "release_convention.hpp"

#include <cstdio>

namespace talus::cli {
namespace {

ReleaseThickness other_than(ReleaseThickness thickness) {
  return thickness == ReleaseThickness::normal ? ReleaseThickness::vertical : ReleaseThickness::normal;
}

const char* describe(ReleaseThickness thickness) {
  return thickness == ReleaseThickness::normal ? "thickness normal to the ground" : "vertical depths";
}

// Why the release was read with its convention.
std::string reason(const ReleaseConvention& c) {
  if (c.choice != ReleaseThicknessChoice::automatic) {
    return std::string("[mud] release_thickness = ") + to_string(c.choice);
  }
  return c.thickness == ReleaseThickness::vertical
             ? "auto: a raster of negative depths, taken as the surface lowering of a DEM of difference"
             : "auto: depths given as positive values or attributes";
}

}  // namespace

ReleaseConvention release_convention(const GroundModel& ground, const ReleaseSet& release,
                                     ReleaseThicknessChoice choice) {
  ReleaseConvention c;
  c.choice = choice;
  c.thickness = thickness_for_release(choice, release);
  c.volume = release_volume(ground, release, c.thickness);
  c.other_volume = release_volume(ground, release, other_than(c.thickness));
  return c;
}

std::string release_convention_text(const ReleaseConvention& c) {
  char text[512];
  std::snprintf(text, sizeof text, "depths read as %s (%s): %.0f m3; as %s they would give %.0f m3",
                describe(c.thickness), reason(c).c_str(), c.volume, describe(other_than(c.thickness)),
                c.other_volume);
  return text;
}

nlohmann::ordered_json release_convention_record(const ReleaseConvention& c) {
  const bool normal = c.thickness == ReleaseThickness::normal;
  return {{"depth_measured", to_string(c.thickness)},
          {"release_thickness", to_string(c.choice)},
          {"reason", reason(c)},
          {"volume_m3", {{"normal", normal ? c.volume : c.other_volume}, {"vertical", normal ? c.other_volume : c.volume}}}};
}

}  // namespace talus::cli
