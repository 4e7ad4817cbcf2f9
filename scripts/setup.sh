#!/usr/bin/env bash
# Installs the Debian packages Talus needs (docs/architecture.md section 4) when any is missing.
# Idempotent: prints nothing and touches nothing when every package is already there.
set -euo pipefail

packages=(
  build-essential cmake pkg-config
  libgdal-dev gdal-bin libproj-dev proj-bin libeigen3-dev
  googletest libgtest-dev libgmock-dev libbenchmark-dev
  libcli11-dev libtomlplusplus-dev nlohmann-json3-dev
  python3-gdal python3-matplotlib python3-numpy python3-qgis qgis qgis-providers
  openmpi-bin libopenmpi-dev
  clang libomp-dev libclang-rt-14-dev xvfb time
)

missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
[ ${#missing[@]} -eq 0 ] && exit 0

echo "talus setup: installing ${missing[*]}"
sudo_cmd=()
[ "$(id -u)" -eq 0 ] || sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
"${sudo_cmd[@]}" apt-get update -qq
"${sudo_cmd[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
echo "talus setup: done"
