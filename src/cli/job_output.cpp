#include "job_output.hpp"

#include <cstdarg>
#include <cstdio>
#include <vector>

namespace talus::cli {

void print_line(const std::string& line) {
  std::fputs(line.c_str(), stdout);
  std::fputc('\n', stdout);
  std::fflush(stdout);
}

std::function<void(const std::string&)> rank_say(bool root) {
  if (root) return print_line;
  return [](const std::string&) {};
}

std::string printf_text(const char* format, ...) {
  va_list arguments;
  va_start(arguments, format);
  va_list measuring;
  va_copy(measuring, arguments);
  const int length = std::vsnprintf(nullptr, 0, format, measuring);
  va_end(measuring);
  std::vector<char> text(static_cast<std::size_t>(length > 0 ? length : 0) + 1);
  std::vsnprintf(text.data(), text.size(), format, arguments);
  va_end(arguments);
  return std::string(text.data());
}

}  // namespace talus::cli
