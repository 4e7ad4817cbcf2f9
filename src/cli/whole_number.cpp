// A whole number that an unsigned 64-bit option can hold (whole_number.hpp).
#include "whole_number.hpp"

#include <algorithm>
#include <string>

namespace talus::cli {

CLI::Validator whole_number() {
  return CLI::Validator(
      [](std::string& text) {
        static const std::string largest = "18446744073709551615";  // 2^64 - 1
        const bool digits = !text.empty() && text.find_first_not_of("0123456789") == std::string::npos;
        const std::string significant = digits ? text.substr(std::min(text.find_first_not_of('0'), text.size() - 1)) : "";
        const bool fits = significant.size() < largest.size() || (significant.size() == largest.size() && significant <= largest);
        if (digits && fits) return std::string();
        return "expected a whole number from 0 to " + largest + ", got " + text;
      },
      "N");
}

}  // namespace talus::cli
