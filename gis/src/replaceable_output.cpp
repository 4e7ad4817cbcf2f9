// Outputs proven writable before any work (replaceable_output.hpp).
#include "talus/gis/replaceable_output.hpp"

#include <fcntl.h>
#include <linux/fs.h>
#include <sys/ioctl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

#include "talus/core/errors.hpp"

namespace talus::gis {
namespace {

// "immutable", "append-only" or empty: the inode flags that forbid renaming or removing a file
// or folder even to its owner. Empty too where the file system keeps no such flags.
std::string locking_flag(const std::filesystem::path& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOFOLLOW | O_CLOEXEC);
  if (fd < 0) return {};
  int flags = 0;
  const bool known = ::ioctl(fd, FS_IOC_GETFLAGS, &flags) == 0;
  ::close(fd);
  if (!known) return {};
  if ((flags & FS_IMMUTABLE_FL) != 0) return "immutable";
  if ((flags & FS_APPEND_FL) != 0) return "append-only";
  return {};
}

}  // namespace

void check_replaceable_folder(const std::filesystem::path& folder, const std::string& shown) {
  const std::string refused = shown + ": cannot be replaced: ";
  if (const std::string flag = locking_flag(folder); !flag.empty()) {
    throw InputError(refused + "the folder is " + flag + " (lsattr shows it; chattr -i or -a clears it)");
  }
  if (::faccessat(AT_FDCWD, folder.c_str(), W_OK | X_OK, AT_EACCESS) != 0) {
    throw InputError(refused + "the folder is not writable (" + std::strerror(errno) + ")");
  }
  std::error_code error;
  for (auto entry = std::filesystem::recursive_directory_iterator(folder, error);
       !error && entry != std::filesystem::recursive_directory_iterator(); entry.increment(error)) {
    if (entry->is_symlink()) continue;
    if (const std::string flag = locking_flag(entry->path()); !flag.empty()) {
      throw InputError(refused + entry->path().lexically_relative(folder).string() + " in it is " + flag);
    }
    if (entry->is_directory() && ::faccessat(AT_FDCWD, entry->path().c_str(), W_OK | X_OK, AT_EACCESS) != 0) {
      throw InputError(refused + "its folder " + entry->path().lexically_relative(folder).string() +
                       " is not writable (" + std::strerror(errno) + ")");
    }
  }
  if (error) throw InputError(refused + error.message());
}

void check_replaceable_file(const std::filesystem::path& file, const std::string& shown) {
  const std::filesystem::path folder = file.parent_path().empty() ? std::filesystem::path(".") : file.parent_path();
  const std::filesystem::path probe = folder / ("." + file.filename().string() + ".probe-" + std::to_string(::getpid()));
  const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
  if (fd < 0) {
    throw InputError(shown + ": cannot be written: cannot create a file in " + folder.string() + " (" +
                     std::strerror(errno) + ")");
  }
  ::close(fd);
  ::unlink(probe.c_str());
  if (const std::string flag = locking_flag(file); !flag.empty()) {
    throw InputError(shown + ": cannot be written: the file is " + flag + " (lsattr shows it; chattr -i or -a clears it)");
  }
}

std::filesystem::perms plain_folder_permissions() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return static_cast<std::filesystem::perms>(0777 & ~mask);
}

}  // namespace talus::gis
