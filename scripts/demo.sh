#!/usr/bin/env bash
# The main demo: the Dzhanibekov (intermediate-axis) flip of seed 000's book.
# Integrates the three book scenes with rkmk4 and with the exact flow, writes
# HDF5 trajectories to build/demo/, and prints a short comparison.
# Usage: scripts/demo.sh [BUILD_DIR]   (default build/release)
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
build="${1:-$root/build/release}"
lgi="$build/lgi"
out="$root/build/demo"
mkdir -p "$out"
[ -x "$lgi" ] || { echo "demo: $lgi not found; build first (see README)" >&2; exit 2; }

for axis in 1 2 3; do
  scene="$root/experiments/scenes/dzhanibekov_book_axis$axis.toml"
  for scheme in rkmk4 exact; do
    "$lgi" simulate --scene "$scene" --scheme "$scheme" --dt 1e-3 --save-every 10 \
      --out "$out/book_axis${axis}_$scheme.h5" --force --quiet
  done
done
/usr/bin/python3 "$root/scripts/compare_demo.py" "$out"
