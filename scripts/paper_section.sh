# Sourced by the paper's section scripts (scripts/paper_atlas.sh, scripts/paper_quantum.sh)
# after `set -euo pipefail`, with section=NAME and help_lines='2,Np' set and the script's
# arguments passed on: `source "$(dirname "$0")/paper_section.sh" "$@"`.
# Parses --lgi PATH --data DIR --figs DIR --gen DIR --mode quick|full (all but --mode
# required), and defines root, lgi, data, figs, gen, mode, PY, plots, scenes,
# out (= DATA/NAME), commands (= GEN/NAME_commands.txt, emptied), die() and run():
# run lgi with its arguments, recording the command line with paths relative to the repository.
root="$(cd "$(dirname "$0")/.." && pwd)"
lgi="" data="" figs="" gen="" mode=quick
while [ $# -gt 0 ]; do
  case "$1" in
    --lgi) lgi="$2"; shift ;;
    --data) data="$2"; shift ;;
    --figs) figs="$2"; shift ;;
    --gen) gen="$2"; shift ;;
    --mode) mode="$2"; shift ;;
    -h|--help) sed -n "$help_lines" "$0"; exit 0 ;;
    *) echo "paper_$section: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
for v in lgi data figs gen; do
  [ -n "${!v}" ] || { echo "paper_$section: --$v is required" >&2; exit 2; }
done
case "$mode" in quick|full) ;; *) echo "paper_$section: --mode must be quick or full" >&2; exit 2 ;; esac
die() { echo "paper_$section: $*" >&2; exit 1; }
PY=/usr/bin/python3
plots="$root/scripts/plots"
scenes="$root/experiments/scenes"
out="$data/$section"
mkdir -p "$out" "$figs" "$gen"
commands="$gen/${section}_commands.txt"
: > "$commands"
run() {
  echo "lgi $*" | sed "s|$root/||g; s|$out/||g; s| --force --quiet||" >> "$commands"
  "$lgi" "$@" --force --quiet || die "lgi $1 failed: lgi $*"
}
