#!/usr/bin/env bash
# The main demo: the Dzhanibekov (intermediate-axis) flip of seed 000's book (docs/sources.md).
# Integrates the three book scenes with rkmk4 and with the exact flow, writes
# HDF5 trajectories book_axis{1,2,3}_{rkmk4,exact}.h5 to the output folder,
# and prints a short comparison.
# Usage: scripts/demo.sh [--out DIR] [--build-dir DIR | BUILD_DIR]
#   --out DIR        where the trajectories go (default build/demo; created if missing)
#   --build-dir DIR  the CMake build folder holding lgi (default build/release;
#                    a lone positional BUILD_DIR means the same)
# Writes nothing outside DIR.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="$root/build/release"
out="$root/build/demo"
while [ $# -gt 0 ]; do
  case "$1" in
    --out) [ $# -ge 2 ] || { echo "demo: --out needs a folder" >&2; exit 2; }; out="$2"; shift ;;
    --out=*) out="${1#*=}" ;;
    --build-dir) [ $# -ge 2 ] || { echo "demo: --build-dir needs a folder" >&2; exit 2; }; build="$2"; shift ;;
    --build-dir=*) build="${1#*=}" ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    -*) echo "demo: unknown option '$1' (see --help)" >&2; exit 2 ;;
    *) build="$1" ;;
  esac
  shift
done
lgi="$build/lgi"
[ -x "$lgi" ] || { echo "demo: $lgi not found; build first (see README)" >&2; exit 2; }
mkdir -p "$out"

for axis in 1 2 3; do
  scene="$root/experiments/scenes/dzhanibekov_book_axis$axis.toml"
  for scheme in rkmk4 exact; do
    "$lgi" simulate --scene "$scene" --scheme "$scheme" --dt 1e-3 --save-every 10 \
      --out "$out/book_axis${axis}_$scheme.h5" --force --quiet
  done
done
PYTHONDONTWRITEBYTECODE=1 /usr/bin/python3 "$root/scripts/compare_demo.py" "$out"
