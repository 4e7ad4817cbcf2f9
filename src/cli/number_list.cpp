// Comma-separated numbers for the command-line options (number_list.hpp).
#include "number_list.hpp"

#include <sstream>
#include <stdexcept>

#include "talus/core/errors.hpp"

namespace talus::cli {

std::vector<double> parse_number_list(const std::string& option, const std::string& text) {
  std::vector<double> values;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ',')) {
    try {
      std::size_t used = 0;
      values.push_back(std::stod(part, &used));
      if (used != part.size()) throw std::invalid_argument(part);
    } catch (const std::exception&) {
      throw InputError(option + " " + text + ": '" + part + "' is not a number");
    }
  }
  if (values.empty()) throw InputError(option + " " + text + ": give at least one value");
  return values;
}

}  // namespace talus::cli
