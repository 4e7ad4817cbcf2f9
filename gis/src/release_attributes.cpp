// Reading and checking a release feature's rock-fall attributes (release_attributes.hpp).
#include "talus/gis/release_attributes.hpp"

#include <cctype>
#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string_view>
#include <vector>

#include "talus/core/errors.hpp"
#include "talus/rockfall/release_rock.hpp"

namespace talus::gis {
namespace {

// What a release feature may ask for beyond the rock limits of rock.hpp.
constexpr double kMaxReleaseSpeed = 100.0;    // m/s
constexpr double kMaxReleaseHeight = 1000.0;  // m

// The text without its leading and trailing blanks.
std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t") - first + 1);
}

// A number for a message, to four significant digits.
std::string text_of(double value) {
  std::ostringstream text;
  text.precision(4);
  text << value;
  return text.str();
}

// A whole text as one number ("inf" and "nan" included, so that they are refused by range).
std::optional<double> parse_number(std::string_view text) {
  text = trimmed(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  double value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (text.empty() || error != std::errc() || end != text.data() + text.size()) return std::nullopt;
  return value;
}

// One attribute of the feature: its value as OGR prints it, and as a number when the field is
// numeric; absent when the feature lacks the field or holds NULL or a blank text in it.
struct Attribute {
  std::string name;                    // the contract's spelling, for messages
  std::string text;
  std::optional<double> number;
};

std::optional<Attribute> attribute(const OGRFeature& feature, const char* name) {
  const int index = feature.GetFieldIndex(name);  // case-insensitive
  if (index < 0 || !feature.IsFieldSetAndNotNull(index)) return std::nullopt;
  Attribute value{name, std::string(trimmed(feature.GetFieldAsString(index))), std::nullopt};
  const OGRFieldType type = feature.GetFieldDefnRef(index)->GetType();
  if (type == OFTReal || type == OFTInteger || type == OFTInteger64) value.number = feature.GetFieldAsDouble(index);
  if (value.text.empty() && !value.number) return std::nullopt;
  return value;
}

// The one-line error naming the feature, the field, its value and the problem.
[[noreturn]] void refuse(const std::string& where, const Attribute& value, const std::string& problem) {
  throw InputError(where + ": " + value.name + " " + value.text + ": " + problem);
}

// A numeric field's value, or a text field's text read as a number; refused with `rule` (what
// the value must be) when it is not a number or `accepted` says no.
template <class Accepted>
double number_of(const Attribute& value, const std::string& where, Accepted accepted, const std::string& rule) {
  const std::optional<double> number = value.number ? value.number : parse_number(value.text);
  if (!number) refuse(where, value, "not a number; it " + rule);
  if (!accepted(*number)) refuse(where, value, rule);
  return *number;
}

// The densities a rock may have (rock.hpp).
bool is_density(double value) { return value >= kMinRockDensity && value <= kMaxRockDensity; }

// `shape`: sphere, ellipsoid or box, in any case.
BlockShape shape_of(const Attribute& value, const std::string& where) {
  std::string text = value.text;
  for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (text == "sphere") return BlockShape::sphere;
  if (text == "ellipsoid") return BlockShape::ellipsoid;
  if (text == "box") return BlockShape::box;
  refuse(where, value, "use sphere, ellipsoid or box");
}

// A number D (all three axes) or a text "D" or "A,B,C", in metres, each axis within rock.hpp's limits.
std::array<double, 3> axes_of(const Attribute& value, const std::string& where) {
  const std::string range = "between " + text_of(kMinRockAxis) + " and " + text_of(kMaxRockAxis) + " m";
  std::vector<double> axes;
  if (value.number) {
    axes.assign(3, *value.number);
  } else {
    std::string_view rest = value.text;
    while (true) {
      const auto comma = rest.find(',');
      const auto number = parse_number(rest.substr(0, comma));
      if (!number) refuse(where, value, "give D or A,B,C in metres, each axis " + range);
      axes.push_back(*number);
      if (comma == std::string_view::npos) break;
      rest.remove_prefix(comma + 1);
    }
    if (axes.size() == 1) axes.assign(3, axes[0]);
    if (axes.size() != 3) refuse(where, value, "give D or A,B,C in metres, each axis " + range);
  }
  for (double axis : axes) {
    if (!(axis > kMinRockAxis && axis < kMaxRockAxis)) refuse(where, value, "axes must lie " + range);
  }
  return {axes[0], axes[1], axes[2]};
}

// The allowed densities, for messages.
std::string density_range() {
  return "between " + text_of(kMinRockDensity) + " and " + text_of(kMaxRockDensity) + " kg/m3";
}

// `density`, or `mass` divided by the volume of the feature's rock; never both.
std::optional<double> density_of(const OGRFeature& feature, const ReleaseConditions& shaped, const Rock& run_rock,
                                 const std::string& where) {
  const auto density = attribute(feature, "density");
  const auto mass = attribute(feature, "mass");
  if (density && mass) {
    throw InputError(where + ": density " + density->text + " and mass " + mass->text + ": give one of them, not both");
  }
  if (density) return number_of(*density, where, is_density, "must lie " + density_range());
  if (!mass) return std::nullopt;
  const double kilograms =
      number_of(*mass, where, [](double m) { return m > 0.0 && std::isfinite(m); }, "must be a mass > 0 kg");
  const double volume = release_rock(run_rock, shaped).volume();
  const double value = kilograms / volume;
  if (!is_density(value)) {
    refuse(where, *mass, "gives a density of " + text_of(value) + " kg/m3 (the feature's rock is " + text_of(volume) +
                             " m3); density must lie " + density_range());
  }
  return value;
}

// `vx`, `vy`, `vz`: when any is given, the others are 0; each finite, the speed within the limit.
std::optional<std::array<double, 3>> velocity_of(const OGRFeature& feature, const std::string& where) {
  const std::optional<Attribute> components[3] = {attribute(feature, "vx"), attribute(feature, "vy"),
                                                  attribute(feature, "vz")};
  if (!components[0] && !components[1] && !components[2]) return std::nullopt;
  std::array<double, 3> velocity{0.0, 0.0, 0.0};
  for (int axis = 0; axis < 3; ++axis) {
    if (!components[axis]) continue;
    velocity[axis] = number_of(*components[axis], where, [](double v) { return std::isfinite(v); },
                               "must be a finite number of m/s (the speed at most " + text_of(kMaxReleaseSpeed) + " m/s)");
  }
  const double speed = std::hypot(velocity[0], velocity[1], velocity[2]);
  if (speed > kMaxReleaseSpeed) {
    throw InputError(where + ": vx, vy, vz " + text_of(velocity[0]) + ", " + text_of(velocity[1]) + ", " +
                     text_of(velocity[2]) + ": a speed of " + text_of(speed) + " m/s; it must be at most " +
                     text_of(kMaxReleaseSpeed) + " m/s");
  }
  return velocity;
}

// `release_height`: the height of the rock's lowest point above the ground at release.
std::optional<double> release_height_of(const OGRFeature& feature, const std::string& where) {
  const auto height = attribute(feature, "release_height");
  if (!height) return std::nullopt;
  return number_of(*height, where, [](double h) { return h >= 0.0 && h <= kMaxReleaseHeight; },
                   "must lie between 0 and " + text_of(kMaxReleaseHeight) + " m");
}

}  // namespace

ReleaseConditions read_release_conditions(const OGRFeature& feature, const Rock& run_rock, const std::string& where) {
  ReleaseConditions conditions;
  const auto shape = attribute(feature, "shape");
  const auto size = attribute(feature, "block_size");
  if (shape) conditions.shape = shape_of(*shape, where);
  if (size) conditions.axes = axes_of(*size, where);
  const Rock rock = release_rock(run_rock, conditions);
  if ((shape || size) && rock.shape == BlockShape::sphere && rock.axes.maxCoeff() != rock.axes.minCoeff()) {
    refuse(where, size ? *size : *shape, "a sphere has one diameter; give block_size D, or shape ellipsoid or box");
  }
  conditions.density = density_of(feature, conditions, run_rock, where);
  conditions.velocity = velocity_of(feature, where);
  conditions.release_height = release_height_of(feature, where);
  return conditions;
}

}  // namespace talus::gis
