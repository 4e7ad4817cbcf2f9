// A run's layer set is committed whole (issue 18, item 3): `talus rockfall` killed (SIGKILL) at
// moments spread over a whole run, again and again into one folder, leaves there after every
// kill either the complete previous set or the complete new one (the same files, a run.json of
// one of the two seeds), never a mix, and the next run clears what the killed one staged.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <fstream>
#include <set>
#include <thread>

#include <nlohmann/json.hpp>

#include "run_talus.hpp"
#include "test_paths.hpp"

namespace talus {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> arguments(const fs::path& out, int seed) {
  const auto sample = test::source_dir() / "sample_dem";
  return {test::talus_exe().string(), "rockfall", "--dem", (sample / "dem.tif").string(), "--lithology",
          (sample / "lithology.tif").string(), "--release", (sample / "rockfall_release.gpkg").string(), "--out",
          out.string(), "--runs", "2", "--seed", std::to_string(seed), "--project", "off", "--threads", "2"};
}

// Starts talus; returns its process id.
pid_t start(const std::vector<std::string>& argv_text) {
  const pid_t child = ::fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_WRONLY);
    ::dup2(null, STDOUT_FILENO);
    ::dup2(null, STDERR_FILENO);
    std::vector<char*> argv;
    for (const auto& a : argv_text) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  return child;
}

std::set<std::string> names_in(const fs::path& folder) {
  std::set<std::string> names;
  for (const auto& entry : fs::directory_iterator(folder)) names.insert(entry.path().filename().string());
  return names;
}

int seed_of(const fs::path& out) {
  std::ifstream in(out / "run.json");
  const nlohmann::json record = nlohmann::json::parse(in, nullptr, false);
  return record.is_object() && record.contains("seed") ? record["seed"].get<int>() : -1;
}

TEST(OutputCommit, AKillAtAnyMomentLeavesTheOldOrTheNewCompleteSet) {
  const auto root = test::fresh_folder("output_commit_kill");
  const auto out = root / "out";
  const auto started = std::chrono::steady_clock::now();
  int status = 0;
  ::waitpid(start(arguments(out, 1)), &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  const double run_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - started).count();
  const std::set<std::string> complete = names_in(out);
  ASSERT_GT(complete.size(), 20u);

  int committed = 1, replaced = 0;
  constexpr int kTrials = 12;
  for (int k = 0; k < kTrials; ++k) {
    const int seed = 100 + k;
    const pid_t child = start(arguments(out, seed));
    // Kill moments from the start to twice the first run's time, so that the moments cover the
    // whole run, its commit included, even when the machine is busier than for the first run.
    std::this_thread::sleep_for(std::chrono::duration<double, std::milli>(run_ms * 2.0 * k / (kTrials - 1)));
    ::kill(child, SIGKILL);
    ::waitpid(child, &status, 0);
    ASSERT_TRUE(fs::is_directory(out)) << "trial " << k << ": no output folder";
    EXPECT_EQ(names_in(out), complete) << "trial " << k << ": the folder holds a partial set";
    const int found = seed_of(out);
    ASSERT_TRUE(found == committed || found == seed) << "trial " << k << ": run.json of seed " << found;
    if (found == seed) ++replaced;
    committed = found;
  }
  EXPECT_GT(replaced, 0) << "no run finished: the kill moments did not reach the commit";
  // A last complete run clears the staging folders the killed runs left beside the output.
  ::waitpid(start(arguments(out, 7)), &status, 0);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  EXPECT_EQ(seed_of(out), 7);
  EXPECT_EQ(names_in(root), (std::set<std::string>{"out"}));
}

}  // namespace
}  // namespace talus
