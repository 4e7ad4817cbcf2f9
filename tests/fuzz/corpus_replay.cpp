// A fuzz target without libFuzzer (CMakeLists.txt beside this file): runs its
// LLVMFuzzerTestOneInput once on every file given, and on every file of every folder given, as
// libFuzzer replays a corpus. A finding ends the run as it ends the fuzzer: with a crash, a
// sanitizer report where the build has them, or an exception other than InputError escaping.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size);

namespace {

// `argument` itself, or the regular files of the folder `argument` in name order.
std::vector<std::filesystem::path> input_files(const std::filesystem::path& argument) {
  if (!std::filesystem::is_directory(argument)) return {argument};
  std::vector<std::filesystem::path> files;
  for (const auto& entry : std::filesystem::directory_iterator(argument)) {
    if (entry.is_regular_file()) files.push_back(entry.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// Every byte of `file`.
std::string file_bytes(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

}  // namespace

int main(int argc, char** argv) {
  std::size_t inputs = 0;
  for (int a = 1; a < argc; ++a) {
    for (const std::filesystem::path& file : input_files(argv[a])) {
      std::printf("%s\n", file.c_str());
      std::fflush(stdout);  // the input that fails is the last line printed
      const std::string bytes = file_bytes(file);
      LLVMFuzzerTestOneInput(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
      ++inputs;
    }
  }
  if (inputs == 0) {
    std::fprintf(stderr, "no input files\n");
    return 1;
  }
  std::printf("%zu inputs, no finding\n", inputs);
  return 0;
}
