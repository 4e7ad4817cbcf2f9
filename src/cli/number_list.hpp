// Comma-separated numbers as options take them ("1.2,0.8,0.5", "30,40").
#pragma once

#include <string>
#include <vector>

namespace talus::cli {

// "a,b,c" -> its numbers; throws InputError naming the option when a part is not a number or
// the list is empty.
std::vector<double> parse_number_list(const std::string& option, const std::string& text);

}  // namespace talus::cli
