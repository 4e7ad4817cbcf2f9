#include "test_paths.hpp"

namespace talus::test {

// Compiled in by tests/CMakeLists.txt, so the tests run the same under ctest and by hand.
std::filesystem::path talus_exe() { return TALUS_TEST_EXE; }
std::filesystem::path source_dir() { return TALUS_TEST_SOURCE_DIR; }
std::filesystem::path shared_dir() { return TALUS_TEST_SHARED_DIR; }

std::filesystem::path fresh_folder(const std::string& name) {
  const auto folder = std::filesystem::temp_directory_path() / "talus-tests" / name;
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  return folder;
}

}  // namespace talus::test
