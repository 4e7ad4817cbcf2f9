#include "test_paths.hpp"

#include <unistd.h>

#include <string>

namespace talus::test {

// Compiled in by tests/CMakeLists.txt, so the tests run the same under ctest and by hand.
std::filesystem::path talus_exe() { return TALUS_TEST_EXE; }
std::filesystem::path source_dir() { return TALUS_TEST_SOURCE_DIR; }
std::filesystem::path data_dir() { return source_dir() / "data"; }

namespace {

// One tree per process, since ctest runs every test case as its own process, in parallel;
// removed when the process ends.
struct ProcessTree {
  std::filesystem::path root =
      std::filesystem::temp_directory_path() / "talus-tests" / std::to_string(::getpid());
  ~ProcessTree() {
    std::error_code ignored;
    std::filesystem::remove_all(root, ignored);
  }
};

}  // namespace

std::filesystem::path fresh_folder(const std::string& name) {
  static const ProcessTree tree;
  const auto folder = tree.root / name;
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

}  // namespace talus::test
