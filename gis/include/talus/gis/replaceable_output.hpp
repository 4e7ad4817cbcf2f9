// Proof, before any work, that an output can be written where the user asked (issue 38, item 6;
// docs/layers.md, "Writing as a unit"): a run that would fail only when it writes its results
// is refused at its start instead, with exit code 2 and one line naming the place.
#pragma once

#include <filesystem>
#include <string>

namespace talus::gis {

// An existing folder whose contents a run will replace or add to: the folder and everything
// in it must be neither immutable nor append-only (chattr +i, +a), and the folder must be
// writable by this process. Throws InputError("SHOWN: cannot be replaced: ...").
void check_replaceable_folder(const std::filesystem::path& folder, const std::string& shown);

// A file a run will write by renaming a finished temporary over `file`: a probe file is created
// and removed beside it, and an existing `file` must be neither immutable nor append-only.
// Throws InputError("SHOWN: cannot be written: ...").
void check_replaceable_file(const std::filesystem::path& file, const std::string& shown);

// The permissions a plain mkdir(1) gives a new folder under this process's umask.
std::filesystem::perms plain_folder_permissions();

}  // namespace talus::gis
