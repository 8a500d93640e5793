#!/usr/bin/env bash
# Installs lgi from BUILD_DIR into a fresh prefix, then configures, builds and
# runs tests/install/consumer and examples/custom_scheme against it
# (find_package(lgi CONFIG REQUIRED)), and imports the installed Python module
# (when the build made one) from outside the tree.
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
configure() {  # source dir, build dir
  cmake -S "$1" -B "$2" -G Ninja -DCMAKE_BUILD_TYPE="$(cache_value CMAKE_BUILD_TYPE)" \
        -DCMAKE_CXX_FLAGS="$(cache_value CMAKE_CXX_FLAGS)" -DCMAKE_EXE_LINKER_FLAGS="$(cache_value CMAKE_EXE_LINKER_FLAGS)" \
        -DCMAKE_PREFIX_PATH="$work/prefix" > "$2.configure.log"
  cmake --build "$2" > "$2.build.log"
}
configure "$here/consumer" "$work/consumer"
"$work/consumer/lie_only"
"$work/consumer/run_scene" "$scenes/free_body_hlw.toml" rkmk4
"$work/prefix/bin/lgi" schemes --family RKMK > /dev/null
# The installed sweep specs find the installed scenes.
"$work/prefix/bin/lgi" sweep --spec "$work/prefix/share/lgi/sweeps/free_body_grid.toml" --out "$work/grid.h5" --quiet > /dev/null
test -s "$work/grid.h5"
# The scheme added out of tree (docs/extending.md): registered, simulated, verified.
configure "$here/../../examples/custom_scheme" "$work/custom_scheme"
"$work/custom_scheme/custom_scheme" "$work/custom_scheme/rkmk3_heun.h5" > "$work/custom_scheme.log"
grep -q "every stated fact holds" "$work/custom_scheme.log"
test -s "$work/custom_scheme/rkmk3_heun.h5"
# The Python module, installed under the prefix and imported from elsewhere (it finds the installed scenes).
module_dir=$(find "$work/prefix" -type d -path "*/dist-packages/lgi" | head -n 1)
if [ -n "$module_dir" ]; then
  (cd "$work" && PYTHONPATH="$(dirname "$module_dir")" /usr/bin/python3 -c \
    "import lgi, os; r = lgi.simulate(lgi.Scene.from_file(os.path.join(lgi.scenes_dir(), 'dzhanibekov_book_axis2.toml')), 'rkmk4', 1.0, dt=1e-3); assert r.t[-1] == 1.0, r.t[-1]; assert lgi.scenes_dir().startswith('$work/prefix')")
fi
echo "check_install: ok"
