#!/usr/bin/env bash
# Installing Talus as a user would (ctest label install; docs/install.md): `cmake --install` into
# a fresh prefix, the installed program run on the installed sample scene from another working
# folder, and `cpack -G DEB` whose package holds the same files and depends on runtime libraries
# only. Prints one line per problem; exit 0 when there is none.
#
# usage: install_test.sh BUILD_DIR VERSION
set -uo pipefail
build=$(cd "$1" && pwd)
version=$2
work=$(mktemp -d "${TMPDIR:-/tmp}/talus-install-test.XXXXXX")
trap 'rm -rf "$work"' EXIT
problems=0
problem() { echo "install test: $*"; problems=$((problems + 1)); }

prefix="$work/prefix"
cmake --install "$build" --prefix "$prefix" >"$work/install.log" 2>&1 || { cat "$work/install.log"; problem "cmake --install failed"; exit 1; }
for file in bin/talus share/talus/qgis/talus_processing/metadata.txt share/talus/qgis/talus_processing/provider.py \
            share/talus/qgis/talus-qgis-plugin.zip share/talus/examples/sample_dem/study.toml \
            share/talus/examples/sample_dem/dem.tif share/doc/talus/README.md share/doc/talus/docs/architecture.md \
            share/doc/talus/docs/install.md; do
  [ -f "$prefix/$file" ] || problem "$file not installed"
done

# The installed program's version line names the version and a commit.
version_line=$("$prefix/bin/talus" --version)
[[ $version_line =~ ^talus\ ${version//./\\.}\ \(commit\ ([0-9a-f]{40}(-modified)?|unknown)\)$ ]] \
  || problem "talus --version printed '$version_line'"
commit=${BASH_REMATCH[1]:-}

# A run from a folder that is neither the source nor the build tree, on the installed scene.
mkdir "$work/elsewhere"
cd "$work/elsewhere" || exit 1
scene=../prefix/share/talus/examples/sample_dem
if ! ../prefix/bin/talus rockfall --dem $scene/dem.tif --lithology $scene/lithology.tif --vegetation $scene/vegetation.tif \
       --release $scene/rockfall_release.gpkg --out out --runs 2 --project off >run.out 2>run.err; then
  cat run.err
  problem "the installed talus rockfall failed"
fi
for layer in reach_probability energy_p95 intensity; do
  [ -f "out/$layer.tif" ] && [ -f "out/$layer.qml" ] || problem "out/$layer.tif or its style is missing"
done
grep -q "\"version\": \"$version\"" out/run.json || problem "run.json does not record version $version"
grep -q "\"git_commit\": \"$commit\"" out/run.json || problem "run.json does not record commit $commit"

# The Debian package: the installed files under /usr, and runtime dependencies only.
cpack -G DEB --config "$build/CPackConfig.cmake" -B "$work/package" >"$work/cpack.log" 2>&1 \
  || { cat "$work/cpack.log"; problem "cpack -G DEB failed"; exit 1; }
deb=$(ls "$work"/package/talus_*.deb 2>/dev/null | head -n 1)
if [ -z "$deb" ]; then
  problem "cpack wrote no talus_*.deb"
else
  contents=$(dpkg-deb -c "$deb")
  for file in ./usr/bin/talus ./usr/share/talus/qgis/talus_processing/metadata.txt \
              ./usr/share/talus/qgis/talus-qgis-plugin.zip ./usr/share/talus/examples/sample_dem/study.toml \
              ./usr/share/doc/talus/README.md; do
    grep -q " $file\$" <<<"$contents" || problem "the package lacks $file"
  done
  depends=$(dpkg-deb -f "$deb" Depends)
  grep -q 'libgdal' <<<"$depends" || problem "the package does not depend on GDAL's library: '$depends'"
  ! grep -qE -- '-dev\b|cmake|googletest|libgtest|libbenchmark' <<<"$depends" \
    || problem "the package depends on build tools: '$depends'"
  [ "$(dpkg-deb -f "$deb" Version)" = "$version" ] || problem "the package's version is not $version"
fi

[ $problems -eq 0 ] || exit 1
echo "install test: prefix, installed run and Debian package as expected (Depends: $depends)"
