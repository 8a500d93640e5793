#!/usr/bin/env bash
# Installs lgi from BUILD_DIR into a fresh prefix, then configures, builds and
# runs tests/install/consumer against it (find_package(lgi CONFIG REQUIRED)).
# usage: check_install.sh BUILD_DIR WORK_DIR SCENES_DIR
set -euo pipefail
build=$1 work=$2 scenes=$3
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work" && mkdir -p "$work"
cmake --install "$build" --prefix "$work/prefix" > "$work/install.log"
test -x "$work/prefix/bin/lgi"
test -f "$work/prefix/lib/cmake/lgi/lgiConfig.cmake"
cmake -S "$here/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log"
cmake --build "$work/consumer" > "$work/build.log"
"$work/consumer/lie_only"
"$work/consumer/run_scene" "$scenes/free_body_hlw.toml" rkmk4
"$work/prefix/bin/lgi" schemes --family RKMK > /dev/null
echo "check_install: ok"
