#!/usr/bin/env bash
# Fuzzes lgi's readers of hostile text with libFuzzer (clang, ASan + UBSan):
# the scene reader and the sweep-spec reader (fuzz/). Builds the `fuzz`
# preset, then runs each harness for SECONDS from the seed corpus (the
# shipped scenes and specs, and tests/fuzz_regressions/<harness>/) with the
# dictionary fuzz/lgi.dict. Exits 1 on any finding, after copying the input
# that triggered it to tests/fuzz_regressions/<harness>/ (replayed by CTest's
# fuzz_regressions in every default run); prints executions and coverage.
# usage: scripts/fuzz.sh [--seconds N] [--work DIR]   (default 30 s per harness, DIR build/fuzz/work)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=30
work="$root/build/fuzz/work"
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    -h|--help) sed -n '2,9p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "fuzz.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
cd "$root"
cmake --preset fuzz > /dev/null
cmake --build --preset fuzz > /dev/null
status=0
for harness in scene_reader sweep_spec; do
  seeds="$root/experiments/scenes"
  [ "$harness" = sweep_spec ] && seeds="$root/experiments/sweeps"
  corpus="$work/$harness"
  artifacts="$work/$harness-artifacts/"
  mkdir -p "$corpus" "$artifacts"
  log="$work/$harness.log"
  if "$root/build/fuzz/fuzz/fuzz_$harness" -dict="$root/fuzz/lgi.dict" -max_total_time="$seconds" \
       -print_final_stats=1 -artifact_prefix="$artifacts" -rss_limit_mb=2048 \
       "$corpus" "$seeds" "$root/tests/fuzz_regressions/$harness" > "$log" 2>&1; then
    execs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | grep -o '[0-9]*$')
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
    echo "fuzz $harness: $execs executions in ${seconds} s, $cov, no finding"
  else
    status=1
    for f in "$artifacts"*; do
      [ -f "$f" ] || continue
      cp "$f" "$root/tests/fuzz_regressions/$harness/"
      echo "fuzz $harness: FINDING $(basename "$f") (copied to tests/fuzz_regressions/$harness/; log $log)" >&2
    done
    grep -E 'ERROR|SUMMARY|bad message' "$log" | head -5 >&2 || true
  fi
done
exit $status
