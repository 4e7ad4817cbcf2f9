// Materials tables in TOML (format in docs/materials.md): reading, with one-line errors that
// name the file and the problem, and writing a table that reads back unchanged.
#include "talus/gis/materials_file.hpp"

#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <sstream>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include <toml++/toml.h>

#include "talus/core/errors.hpp"

namespace talus::gis {
namespace {

// One number of a lithology class: its key in the file, its member, the comment written beside
// it (symbol and unit), and its unit and range (materials_fields).
struct LithologyNumber {
  std::string_view key;
  double LithologyClass::*member;
  std::string_view comment, unit;
  double min, max;
};

// The ranges hold every class of docs/references.md's tables with room to spare; beyond them
// the piston carpet's steps or the bounce model stop meaning anything.
constexpr std::array<LithologyNumber, 9> lithology_numbers{{
    {"elastic_slope", &LithologyClass::elastic_slope, "k1, Pa/m", "Pa/m", 1e3, 1e12},
    {"yield_pressure", &LithologyClass::yield_pressure, "Pa", "Pa", 1e2, 1e10},
    {"plastic_slope", &LithologyClass::plastic_slope, "k2, Pa/m", "Pa/m", 1e2, 1e12},
    {"unloading_slope", &LithologyClass::unloading_slope, "k3, Pa/m", "Pa/m", 1e3, 1e13},
    {"friction", &LithologyClass::friction, "sliding, tan of the friction angle, -", "-", 0, 10},
    {"rolling_friction", &LithologyClass::rolling_friction, "rolling, mu_r, -", "-", 0, 10},
    {"restitution_normal", &LithologyClass::restitution_normal, "fast mode, -", "-", 0, 1},
    {"restitution_tangential", &LithologyClass::restitution_tangential, "fast mode, -", "-", 0, 1},
    {"noise_amplitude", &LithologyClass::noise_amplitude, "m", "m", 0, 10},
}};

// The vegetation's one number, the deperdition coefficient c, with its unit and range.
constexpr MaterialsField kDeperdition{"vegetation", "deperdition", "1/m", "deperdition coefficient c", 0, 10};

constexpr std::array<std::string_view, 4> top_level_keys{"default_lithology", "default_vegetation",
                                                         "lithology", "vegetation"};

constexpr auto lithology_keys = [] {
  std::array<std::string_view, lithology_numbers.size() + 2> keys{"code", "name"};
  for (std::size_t k = 0; k < lithology_numbers.size(); ++k) keys[k + 2] = lithology_numbers[k].key;
  return keys;
}();

constexpr std::array<std::string_view, 3> vegetation_keys{"code", "name", "deperdition"};

// Shortest text that reads back as the same double, always with a '.' so that TOML sees a
// float, in scientific notation when large or tiny: 50000 -> "5.0e4", 0.355 -> "0.355", 0 -> "0.0".
std::string toml_number(double value) {
  if (std::isnan(value)) return "nan";
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  const double size = std::abs(value);
  const auto format = size >= 1e4 || (size > 0 && size < 1e-4) ? std::chars_format::scientific
                                                                 : std::chars_format::fixed;
  std::array<char, 400> buffer{};
  const auto end = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value, format).ptr;
  const std::string shortest(buffer.data(), end);
  const auto e = shortest.find('e');
  std::string mantissa = shortest.substr(0, e);
  if (mantissa.find('.') == std::string::npos) mantissa += ".0";
  if (e == std::string::npos) return mantissa;
  return mantissa + "e" + std::to_string(std::stoi(shortest.substr(e + 1)));
}

// A TOML basic string: quotes, backslashes and control characters escaped.
std::string toml_string(const std::string& text) {
  std::string quoted = "\"";
  for (const char c : text) {
    const auto byte = static_cast<unsigned char>(c);
    if (c == '"' || c == '\\') {
      quoted += '\\';
      quoted += c;
    } else if (byte < 0x20 || byte == 0x7F) {
      std::array<char, 8> escape{};
      std::snprintf(escape.data(), escape.size(), "\\u%04X", static_cast<unsigned>(byte));
      quoted += escape.data();
    } else {
      quoted += c;
    }
  }
  return quoted + "\"";
}

// "key = value", with the comment aligned after it.
std::string toml_line(std::string_view key, const std::string& value, std::string_view comment) {
  std::string text = std::string(key) + " = " + value;
  if (!comment.empty()) {
    text.resize(std::max<std::size_t>(text.size() + 1, 34), ' ');
    text += "# ";
    text += comment;
  }
  return text + "\n";
}

std::string type_name(const toml::node& node) {
  std::ostringstream text;
  text << node.type();
  return text.str();
}

std::string at_line(const toml::node& node) {
  const auto line = node.source().begin.line;
  return line == 0 ? std::string() : " (line " + std::to_string(line) + ")";
}

// "'key'" followed by where it is (" in lithology class 4", or nothing at the top level).
std::string quoted(std::string_view key, const std::string& where) {
  std::string text = "'";
  text.append(key);
  text += "'";
  return text + where;
}

std::string one_line(std::string_view text) {
  std::string flat(text);
  std::replace_if(flat.begin(), flat.end(), [](char c) { return c == '\n' || c == '\r'; }, ' ');
  return flat;
}

// Reads one file; every check throws an InputError that starts with the file's name.
class MaterialsReader {
 public:
  explicit MaterialsReader(std::filesystem::path path) : path_(std::move(path)) {}

  MaterialsTable read() const {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path_, error)) fail("materials file not found");
    toml::table root;
    try {
      root = toml::parse_file(path_.string());
    } catch (const toml::parse_error& e) {
      const auto& where = e.source().begin;
      if (where.line == 0) fail("cannot read the file: " + one_line(e.description()));
      fail("TOML syntax error at line " + std::to_string(where.line) + ", column " + std::to_string(where.column) +
           ": " + one_line(e.description()));
    }
    check_keys(root, top_level_keys, "at the top level");

    MaterialsTable table;
    table.default_lithology = integer(top_level(root, "default_lithology"), "default_lithology", "");
    table.default_vegetation = integer(top_level(root, "default_vegetation"), "default_vegetation", "");
    for (const toml::table& entry : classes(root, "lithology")) {
      table.lithology.push_back(lithology(entry, table.lithology.size() + 1));
      const LithologyClass& added = table.lithology.back();
      if (table.find_lithology(added.code) != &added) {
        fail("duplicate lithology code " + std::to_string(added.code) + at_line(entry));
      }
    }
    for (const toml::table& entry : classes(root, "vegetation")) {
      table.vegetation.push_back(vegetation(entry, table.vegetation.size() + 1));
      const VegetationClass& added = table.vegetation.back();
      if (table.find_vegetation(added.code) != &added) {
        fail("duplicate vegetation code " + std::to_string(added.code) + at_line(entry));
      }
    }
    if (table.find_lithology(table.default_lithology) == nullptr) {
      fail("default_lithology = " + std::to_string(table.default_lithology) +
           " is not one of the [[lithology]] classes");
    }
    if (table.find_vegetation(table.default_vegetation) == nullptr) {
      fail("default_vegetation = " + std::to_string(table.default_vegetation) +
           " is not one of the [[vegetation]] classes");
    }
    return table;
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw InputError(path_.string() + " (materials): " + problem);
  }

  template <std::size_t N>
  void check_keys(const toml::table& table, const std::array<std::string_view, N>& allowed,
                  const std::string& where) const {
    for (const auto& [key, node] : table) {
      if (std::find(allowed.begin(), allowed.end(), key.str()) == allowed.end()) {
        fail("unknown key '" + std::string(key.str()) + "' " + where + at_line(node));
      }
    }
  }

  const toml::node& top_level(const toml::table& root, std::string_view key) const {
    const toml::node* node = root.get(key);
    if (node == nullptr) fail("missing field '" + std::string(key) + "' at the top level");
    return *node;
  }

  // A field of the class `where` (e.g. "lithology class 4") in the table `entry`.
  const toml::node& field(const toml::table& entry, std::string_view key, const std::string& where) const {
    const toml::node* node = entry.get(key);
    if (node == nullptr) fail("missing field '" + std::string(key) + "' in " + where + at_line(entry));
    return *node;
  }

  // `where` is empty for top-level keys, else " in <class>".
  int integer(const toml::node& node, std::string_view key, const std::string& where) const {
    const auto* value = node.as_integer();
    if (value == nullptr) {
      fail(quoted(key, where) + " must be an integer (found: " + type_name(node) + ")" + at_line(node));
    }
    const std::int64_t v = value->get();
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max()) {
      fail(quoted(key, where) + " is out of range: " + std::to_string(v) + at_line(node));
    }
    return static_cast<int>(v);
  }

  double number(const toml::node& node, std::string_view key, const std::string& where) const {
    if (!node.is_number()) {
      fail(quoted(key, where) + " must be a number (found: " + type_name(node) + ")" + at_line(node));
    }
    const double v = node.value<double>().value();
    if (!std::isfinite(v)) fail(quoted(key, where) + " must be finite" + at_line(node));
    return v;
  }

  // A number within [min, max], or the key, the value and the range.
  void check_range(const toml::node& node, std::string_view key, const std::string& where, double value, double min,
                   double max, std::string_view unit) const {
    if (value >= min && value <= max) return;
    std::string expected = "expected " + toml_number(min) + " to " + toml_number(max);
    if (unit != "-") expected += " " + std::string(unit);
    fail(quoted(key, where) + " = " + toml_number(value) + at_line(node) + ": " + expected);
  }

  std::string text(const toml::node& node, std::string_view key, const std::string& where) const {
    const auto* value = node.as_string();
    if (value == nullptr) {
      fail(quoted(key, where) + " must be a string (found: " + type_name(node) + ")" + at_line(node));
    }
    return value->get();
  }

  // The [[kind]] tables of the file, in order.
  std::vector<std::reference_wrapper<const toml::table>> classes(const toml::table& root,
                                                                 std::string_view kind) const {
    const std::string name(kind);
    const toml::node* node = root.get(kind);
    if (node == nullptr) fail("no [[" + name + "]] classes");
    const auto* array = node->as_array();
    if (array != nullptr && array->empty()) fail("no [[" + name + "]] classes" + at_line(*node));
    if (array == nullptr || !array->is_array_of_tables()) {
      fail("'" + name + "' must be a list of [[" + name + "]] tables (found: " + type_name(*node) + ")" +
           at_line(*node));
    }
    std::vector<std::reference_wrapper<const toml::table>> tables;
    for (const toml::node& element : *array) tables.emplace_back(*element.as_table());
    return tables;
  }

  // Checks the keys, reads code and name, and returns how messages name the class.
  template <typename Class, std::size_t N>
  std::string identify(const toml::table& entry, const std::array<std::string_view, N>& keys,
                       const std::string& kind, std::size_t position, Class& out) const {
    const std::string entry_name = kind + " entry " + std::to_string(position);
    check_keys(entry, keys, "in " + entry_name);
    out.code = integer(field(entry, "code", entry_name), "code", " in " + entry_name);
    const std::string class_name = kind + " class " + std::to_string(out.code);
    out.name = text(field(entry, "name", class_name), "name", " in " + class_name);
    return class_name;
  }

  LithologyClass lithology(const toml::table& entry, std::size_t position) const {
    LithologyClass c;
    const std::string where = identify(entry, lithology_keys, "lithology", position, c);
    for (const LithologyNumber& n : lithology_numbers) {
      const toml::node& node = field(entry, n.key, where);
      c.*n.member = number(node, n.key, " in " + where);
      check_range(node, n.key, " in " + where, c.*n.member, n.min, n.max, n.unit);
    }
    const std::string at = where + at_line(entry) + ": ";
    if (!(0 < c.plastic_slope && c.plastic_slope < c.elastic_slope && c.elastic_slope < c.unloading_slope)) {
      fail(at + "the stress cycle needs 0 < plastic_slope < elastic_slope < unloading_slope, got " +
           toml_number(c.plastic_slope) + ", " + toml_number(c.elastic_slope) + ", " +
           toml_number(c.unloading_slope));
    }
    return c;
  }

  VegetationClass vegetation(const toml::table& entry, std::size_t position) const {
    VegetationClass c;
    const std::string where = identify(entry, vegetation_keys, "vegetation", position, c);
    const toml::node& node = field(entry, kDeperdition.key, where);
    c.deperdition = number(node, kDeperdition.key, " in " + where);
    check_range(node, kDeperdition.key, " in " + where, c.deperdition, kDeperdition.min, kDeperdition.max,
                kDeperdition.unit);
    return c;
  }

  std::filesystem::path path_;
};

}  // namespace

const std::vector<MaterialsField>& materials_fields() {
  static const std::vector<MaterialsField> fields = [] {
    std::vector<MaterialsField> out;
    for (const LithologyNumber& n : lithology_numbers) out.push_back({"lithology", n.key, n.unit, n.comment, n.min, n.max});
    out.push_back(kDeperdition);
    return out;
  }();
  return fields;
}

MaterialsTable read_materials(const std::filesystem::path& path) { return MaterialsReader(path).read(); }

std::string materials_to_toml(const MaterialsTable& table) {
  std::string text = "# Talus materials table: lithology and vegetation classes (format: docs/materials.md).\n";
  text += toml_line("default_lithology", std::to_string(table.default_lithology),
                    "class used where no lithology raster is given");
  text += toml_line("default_vegetation", std::to_string(table.default_vegetation),
                    "class used where no vegetation raster is given");
  for (const LithologyClass& c : table.lithology) {
    text += "\n[[lithology]]\n";
    text += toml_line("code", std::to_string(c.code), "value in the lithology raster");
    text += toml_line("name", toml_string(c.name), "");
    for (const LithologyNumber& n : lithology_numbers) {
      text += toml_line(n.key, toml_number(c.*n.member), n.comment);
    }
  }
  for (const VegetationClass& c : table.vegetation) {
    text += "\n[[vegetation]]\n";
    text += toml_line("code", std::to_string(c.code), "value in the vegetation raster");
    text += toml_line("name", toml_string(c.name), "");
    text += toml_line("deperdition", toml_number(c.deperdition), "c, 1/m");
  }
  return text;
}

}  // namespace talus::gis
