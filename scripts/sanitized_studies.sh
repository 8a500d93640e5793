#!/usr/bin/env bash
# Runs lgi's long studies under AddressSanitizer + UBSan (an lgi built with
# the sanitize preset) and checks that they make 0 reports: the full stress
# suite (lgi stress, every case and variant against every scheme) and the
# long-time study of the paper (scripts/build_paper.sh, full mode: the same
# scenes, schemes, steps and spans). The sanitize preset compiles with
# -fno-sanitize-recover=all, so a report ends the run that made it; a run
# fails if its exit status is not 0 or its stderr holds a sanitizer report
# (AddressSanitizer, LeakSanitizer, "runtime error:"). Prints one line per
# run with its time; exits 1 if any failed.
# usage: scripts/sanitized_studies.sh --lgi PATH --study stress|long-time [--quick] [--out DIR]
#   --quick   the stress suite's --quick and the paper's quick long-time cases (minutes, not hours)
#   --out     folder for the results and logs (default: a temporary folder, removed at the end)
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
lgi="" study="" quick=0 out=""
while [ $# -gt 0 ]; do
  case "$1" in
    --lgi) lgi=$2; shift 2 ;;
    --study) study=$2; shift 2 ;;
    --quick) quick=1; shift ;;
    --out) out=$2; shift 2 ;;
    -h|--help) sed -n '2,15p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "sanitized_studies: unknown argument $1 (see --help)" >&2; exit 2 ;;
  esac
done
[ -x "$lgi" ] || { echo "sanitized_studies: --lgi: no lgi at '$lgi'" >&2; exit 2; }
case "$study" in stress|long-time) ;; *) echo "sanitized_studies: --study stress or long-time" >&2; exit 2 ;; esac
if [ -z "$out" ]; then
  out=$(mktemp -d -t lgi-sanitized-XXXXXX)
  trap 'rm -rf "$out"' EXIT
fi
mkdir -p "$out"
scenes="$root/experiments/scenes"
export ASAN_OPTIONS="detect_leaks=1:halt_on_error=1:${ASAN_OPTIONS:-}"
export UBSAN_OPTIONS="halt_on_error=1:print_stacktrace=1:${UBSAN_OPTIONS:-}"
failed=0 runs=0

# run NAME ARGS...: one lgi run, its stderr kept in $out/NAME.log.
run() {
  local name=$1; shift
  local log="$out/$name.log" start=$SECONDS status=0
  "$lgi" "$@" > /dev/null 2> "$log" || status=$?
  runs=$((runs + 1))
  local reports
  reports=$(grep -cE 'ERROR: (AddressSanitizer|LeakSanitizer)|runtime error:' "$log" || true)
  if [ "$status" -ne 0 ] || [ "$reports" -ne 0 ]; then
    failed=$((failed + 1))
    echo "sanitized $name: FAILED (exit $status, $reports sanitizer reports; log $log)" >&2
    grep -m5 -E 'ERROR|SUMMARY|runtime error|lgi:' "$log" >&2 || true
  else
    echo "sanitized $name: ok, 0 reports ($((SECONDS - start)) s)"
  fi
}

if [ "$study" = stress ]; then
  run stress stress $([ $quick = 1 ] && echo --quick) --scenes-dir "$scenes" --out "$out/stress.h5" --force --quiet
else
  # The long-time cases of scripts/build_paper.sh, full or --quick.
  . "$root/scripts/long_time_cases.sh"
  long_time_cases "$([ $quick = 1 ] && echo quick || echo full)"
  for spec in "${lt_cases[@]}"; do
    IFS='|' read -r scene dt t_end schemes <<< "$spec"
    for s in $schemes; do
      run "long-time_${scene}_$(tr '/@' '__' <<< "$s")" long-time --scene "$scenes/$scene.toml" --scheme "$s" \
        --dt "$dt" --t-end "$t_end" --out "$out/lt_${scene}_$(tr '/@' '__' <<< "$s").h5" --force --quiet
    done
  done
fi
echo "sanitized_studies $study: $runs runs, $failed failed"
[ "$failed" -eq 0 ]
