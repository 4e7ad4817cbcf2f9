// Runs the built-in QGIS project script on a committed run (run_project.hpp).
#include "run_project.hpp"

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <system_error>
#include <thread>
#include <vector>

#include "run_project_script.hpp"
#include "talus/core/errors.hpp"

namespace talus::cli {
namespace {

std::filesystem::path python_program() {
  const char* named = std::getenv("TALUS_PYTHON");
  return named != nullptr && *named != '\0' ? std::filesystem::path(named) : std::filesystem::path("/usr/bin/python3");
}

std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The last non-empty line of `text`, for a one-line reason.
std::string last_line(const std::string& text) {
  std::size_t end = text.find_last_not_of("\n ");
  if (end == std::string::npos) return {};
  const std::size_t start = text.rfind('\n', end);
  return text.substr(start == std::string::npos ? 0 : start + 1, end - (start == std::string::npos ? 0 : start + 1) + 1);
}

}  // namespace

RunProjectOutcome write_run_project(const std::filesystem::path& staging, const std::filesystem::path& out,
                                    const std::string& process,
                                    const std::filesystem::path& dem, const std::filesystem::path& release,
                                    double timeout_s) {
  const std::filesystem::path python = python_program();
  if (::access(python.c_str(), X_OK) != 0) {
    return {false, true, "no project.qgz or quicklooks: " + python.string() + " (with python3-qgis) is not installed"};
  }
  const auto script = staging / ".run_project.py";
  const auto errors = staging / ".run_project.err";
  {
    std::ofstream file(script);
    file << kRunProjectScript;
    if (!file) return {false, false, "no project.qgz or quicklooks: cannot write " + script.string()};
  }
  const std::vector<std::string> arguments = {python.string(),
                                              script.string(),
                                              std::filesystem::absolute(staging).string(),
                                              process,
                                              std::filesystem::absolute(dem).string(),
                                              release.empty() ? std::string() : std::filesystem::absolute(release).string()};
  const auto started = std::chrono::steady_clock::now();
  const pid_t child = ::fork();
  if (child == 0) {
    const int err = ::open(errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int null = ::open("/dev/null", O_WRONLY);
    if (err >= 0) ::dup2(err, STDERR_FILENO);
    if (null >= 0) ::dup2(null, STDOUT_FILENO);
    std::vector<char*> argv;
    for (const auto& a : arguments) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int status = 0;
  bool timed_out = false;
  if (child < 0) return {false, false, "no project.qgz or quicklooks: cannot start " + python.string()};
  while (::waitpid(child, &status, WNOHANG) == 0) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count() > timeout_s) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      timed_out = true;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  const std::string reason = last_line(read_text(errors));
  std::error_code ignored;
  std::filesystem::remove(script, ignored);
  std::filesystem::remove(errors, ignored);
  for (const char* part : {".project.part.qgz", ".hillshade.part.tif", ".quicklook.part"})
    std::filesystem::remove_all(staging / part, ignored);
  if (timed_out) return {false, false, "no project.qgz or quicklooks: QGIS took longer than " + std::to_string(int(timeout_s)) + " s"};
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
    const bool no_qgis = reason.find("No module named 'qgis'") != std::string::npos;
    return {false, no_qgis, "no project.qgz or quicklooks: " + (reason.empty() ? "the QGIS script failed" : reason)};
  }
  char text[64];
  std::snprintf(text, sizeof text, " (%.1f s)", seconds);
  return {true, false, "QGIS project " + (out / "project.qgz").string() + " and quicklooks in " + (out / "quicklook").string() + text};
}

bool project_wanted(const std::string& setting) {
  if (setting == "on") return true;
  if (setting == "off") return false;
  throw InputError("--project " + setting + ": use on or off");
}

std::string write_project_if_wanted(bool wanted, const std::filesystem::path& staging, const std::filesystem::path& out,
                                    const std::string& process, const std::filesystem::path& dem,
                                    const std::filesystem::path& release) {
  if (!wanted) return {};
  const RunProjectOutcome outcome = write_run_project(staging, out, process, dem, release, 600.0);
  const char* kind = outcome.written ? "" : outcome.qgis_missing ? "note: " : "problem: ";
  return kind + outcome.message;
}

}  // namespace talus::cli
