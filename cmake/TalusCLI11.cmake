# CLI11 command-line parser (Debian: libcli11-dev), header only.
find_package(CLI11 CONFIG REQUIRED)
