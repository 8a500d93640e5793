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
# The consumer is compiled as lgi was (the sanitize preset's flags must reach its link too).
cache_value() { sed -n "s/^$1:[A-Z]*=//p" "$build/CMakeCache.txt"; }
cmake -S "$here/consumer" -B "$work/consumer" -G Ninja -DCMAKE_BUILD_TYPE="$(cache_value CMAKE_BUILD_TYPE)" \
      -DCMAKE_CXX_FLAGS="$(cache_value CMAKE_CXX_FLAGS)" -DCMAKE_EXE_LINKER_FLAGS="$(cache_value CMAKE_EXE_LINKER_FLAGS)" \
      -DCMAKE_PREFIX_PATH="$work/prefix" > "$work/configure.log"
cmake --build "$work/consumer" > "$work/build.log"
"$work/consumer/lie_only"
"$work/consumer/run_scene" "$scenes/free_body_hlw.toml" rkmk4
"$work/prefix/bin/lgi" schemes --family RKMK > /dev/null
echo "check_install: ok"
