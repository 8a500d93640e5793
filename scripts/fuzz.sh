#!/usr/bin/env bash
# Fuzzes lgi's readers of hostile input with libFuzzer (clang, ASan + UBSan;
# fuzz/): the scene reader, the sweep-spec reader, the command line of every
# subcommand (parsed and checked, never run) and the HDF5 files lgi reads
# back (sweep and long-time resume files, finished sweeps). Builds what the
# chosen harnesses need in the `fuzz` preset (build/fuzz; the command-line
# harness needs the whole instrumented library, the others a few files),
# then runs each for SECONDS from its seed corpus (shipped scenes, specs,
# fuzz/seeds/, HDF5 files written at build time) and
# tests/fuzz_regressions/<harness>/, with its dictionary. Exits 1 on any
# finding, after copying the input that triggered it to
# tests/fuzz_regressions/<harness>/ (replayed by CTest in every default
# run); prints executions, exec/s and libFuzzer's cov: and ft: per harness.
# usage: scripts/fuzz.sh [--seconds N] [--harness A,B] [--work DIR]
#   (default 30 s per harness, every harness: scene_reader,sweep_spec,command_line,h5_readers;
#    DIR build/fuzz/work)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
seconds=30
harnesses="scene_reader,sweep_spec,command_line,h5_readers"
work="$root/build/fuzz/work"
while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) seconds=$2; shift 2 ;;
    --harness) harnesses=$2; shift 2 ;;
    --work) work=$2; shift 2 ;;
    -h|--help) sed -n '2,17p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "fuzz.sh: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
cd "$root"
IFS=, read -r -a list <<< "$harnesses"
targets=()
for harness in "${list[@]}"; do
  case "$harness" in
    scene_reader|sweep_spec|command_line) targets+=("fuzz_$harness") ;;
    h5_readers) targets+=("fuzz_$harness" fuzz_h5_seed_files) ;;
    *) echo "fuzz.sh: unknown harness $harness (see --help)" >&2; exit 2 ;;
  esac
done
cmake --preset fuzz > /dev/null
cmake --build --preset fuzz --target "${targets[@]}" > /dev/null
status=0
for harness in "${list[@]}"; do
  dict="$root/fuzz/lgi.dict"
  case "$harness" in
    scene_reader) seeds="$root/experiments/scenes" ;;
    sweep_spec) seeds="$root/experiments/sweeps" ;;
    command_line) seeds="$root/fuzz/seeds/command_line"; dict="$root/fuzz/command_line.dict" ;;
    h5_readers) seeds="$root/build/fuzz/fuzz/seeds/h5_readers"; dict="$root/fuzz/h5_readers.dict" ;;
  esac
  corpus="$work/$harness"
  artifacts="$work/$harness-artifacts/"
  mkdir -p "$corpus" "$artifacts"
  log="$work/$harness.log"
  # allocator_may_return_null: a corrupted HDF5 file can make libhdf5 itself ask for a block of
  # terabytes (H5C_protect); glibc's malloc returns NULL there and HDF5 reports an error, which is
  # what lgi must handle. ASan would otherwise stop at the request.
  # fuzz/lsan_hdf5.supp: the small block libhdf5 keeps after such a failed request.
  if ASAN_OPTIONS="allocator_may_return_null=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}" \
     LSAN_OPTIONS="suppressions=$root/fuzz/lsan_hdf5.supp${LSAN_OPTIONS:+:$LSAN_OPTIONS}" \
     "$root/build/fuzz/fuzz/fuzz_$harness" -dict="$dict" -max_total_time="$seconds" -timeout=20 \
       -print_final_stats=1 -artifact_prefix="$artifacts" -rss_limit_mb=2048 \
       "$corpus" "$seeds" "$root/tests/fuzz_regressions/$harness" > "$log" 2>&1; then
    execs=$(grep -o 'stat::number_of_executed_units: [0-9]*' "$log" | grep -o '[0-9]*$')
    rate=$(grep -o 'stat::average_exec_per_sec: [0-9]*' "$log" | grep -o '[0-9]*$')
    cov=$(grep -o 'cov: [0-9]*' "$log" | tail -1)
    ft=$(grep -o 'ft: [0-9]*' "$log" | tail -1)
    echo "fuzz $harness: $execs executions in ${seconds} s ($rate/s), $cov, $ft, no finding"
  else
    status=1
    for f in "$artifacts"*; do
      [ -f "$f" ] || continue
      cp "$f" "$root/tests/fuzz_regressions/$harness/"
      echo "fuzz $harness: FINDING $(basename "$f") (copied to tests/fuzz_regressions/$harness/; log $log)" >&2
    done
    grep -E 'ERROR|SUMMARY|bad message|finding|HDF5 would|not one|unexpected' "$log" | head -5 >&2 || true
  fi
done
exit $status
