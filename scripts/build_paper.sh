#!/usr/bin/env bash
# Builds the paper: runs the experiments it needs with lgi, makes the figures
# (scripts/plots/*.py, Debian's /usr/bin/python3), writes the generated tables
# and sentences (paper/generated/), and builds paper/build/lgi.pdf with latexmk.
#
# Usage: scripts/build_paper.sh [--quick] [--out DIR] [--build-dir DIR] [--lgi PATH]
#   --quick        coarse steps, short spans, one timed repeat: a few minutes on
#                  2 cores, the same PDF structure (CI runs this, CTest paper_quick)
#   --out DIR      output folder (default paper/build): DIR/lgi.pdf, DIR/lgi.log,
#                  DIR/build_paper.log, DIR/figures, DIR/data, and then also
#                  DIR/generated and DIR/tex (links to paper/'s sources): with
#                  --out nothing is written in the source tree
#   --build-dir D  the CMake build folder holding lgi (default build/release)
#   --lgi PATH     the lgi executable itself (overrides --build-dir)
#
# Subcommands this lgi lacks (work-precision, long-time, stress, singularity)
# are skipped with a note that appears in the PDF in place of their figures and
# tables; nothing is faked. Any real error (a failed run that should have
# worked, a bad input, a plot or LaTeX error) stops the script with a non-zero
# status. Runs of baselines that may legitimately stop (an Euler-angle chart
# at its singularity) are kept as data, with their status.
# Outputs (default): paper/build/lgi.pdf, paper/build/figures/*.{pdf,png,gif}
# (animations dzhanibekov_book_axis2.gif, prism_edurev.gif),
# paper/build/data/*.h5 (+ .csv), paper/generated/*.tex.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
mode=full
build_dir="$root/build/release"
lgi=""
out_arg=""
while [ $# -gt 0 ]; do
  case "$1" in
    --quick) mode=quick ;;
    --out) [ $# -ge 2 ] || { echo "build_paper: --out needs a folder" >&2; exit 2; }; out_arg="$2"; shift ;;
    --out=*) out_arg="${1#*=}" ;;
    --build-dir) build_dir="$2"; shift ;;
    --build-dir=*) build_dir="${1#*=}" ;;
    --lgi) lgi="$2"; shift ;;
    --lgi=*) lgi="${1#*=}" ;;
    -h|--help) sed -n '2,25p' "$0"; exit 0 ;;
    *) echo "build_paper: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
lgi="${lgi:-$build_dir/lgi}"
die() { echo "build_paper: $*" >&2; exit 1; }
[ -x "$lgi" ] || die "lgi not found at $lgi; build it first (README) or pass --build-dir/--lgi"
lgi="$(cd "$(dirname "$lgi")" && pwd)/$(basename "$lgi")"
PY=/usr/bin/python3
[ -x "$PY" ] || die "$PY not found (scripts/install-deps.sh installs Debian's python3)"
"$PY" -c 'import matplotlib, h5py, numpy, tomllib' 2>/dev/null \
  || die "$PY lacks matplotlib/h5py/numpy (scripts/install-deps.sh)"
command -v latexmk >/dev/null || die "latexmk not found (scripts/install-deps.sh)"

export PYTHONDONTWRITEBYTECODE=1  # no __pycache__ beside the plot scripts
paper="$root/paper"
if [ -n "$out_arg" ]; then
  mkdir -p "$out_arg"
  out="$(cd "$out_arg" && pwd)"
  gen="$out/generated"
else
  out="$paper/build"
  gen="$paper/generated"
fi
data="$out/data"
figs="$out/figures"
notes="$gen/notes"
plots="$root/scripts/plots"
scenes="$root/experiments/scenes"
rm -rf "$data" "$figs" "$gen"
mkdir -p "$data" "$figs" "$gen" "$notes"
t_start=$(date +%s)
log="$out/build_paper.log"
: > "$log"
say() { echo "build_paper: $*" | tee -a "$log" >&2; }
say "mode=$mode lgi=$lgi"

# ── what this lgi offers ─────────────────────────────────────────────────────
subcommands="$("$lgi" --help | sed -n '/^Subcommands:/,$p' | awk 'NR > 1 {print $1}')"
has_sub() { grep -qx "$1" <<<"$subcommands"; }
"$lgi" schemes --json > "$gen/schemes.json"
scheme_list="$("$PY" -c 'import json,sys; [print(s["name"]) for s in json.load(open(sys.argv[1]))]' "$gen/schemes.json")"
has_scheme() { grep -qxF "$1" <<<"$scheme_list"; }
# Schemes among the arguments that exist here (and, with --free, also those for free bodies only).
filter_schemes() {  # filter_schemes any|free NAME...
  local kind="$1"; shift
  "$PY" - "$gen/schemes.json" "$kind" "$@" <<'EOF'
import json, sys
info = {s["name"]: s for s in json.load(open(sys.argv[1]))}
kind = sys.argv[2]
keep = []
for n in sys.argv[3:]:
    s = info.get(n)
    if s is None:
        continue
    scenes = str(s.get("scenes", "any")).lower()
    if kind == "any" and "free" in scenes and "any" not in scenes:
        continue
    keep.append(n)
print(",".join(keep))
EOF
}
missing_note() {  # missing_note NAME TEXT: shown in the PDF in place of figure/table NAME
  printf '%s\n' "$2" > "$notes/$1.tex"
  say "note for $1: $2"
}

# lgi simulate; a non-zero exit is a real error unless the scheme may stop (may_stop=1):
# then its .partial file is kept as data (renamed *.stopped.h5) with its status.
simulate() {  # simulate MAY_STOP OUT.h5 ARGS...
  local may_stop="$1" outf="$2"; shift 2
  local rc=0
  "$lgi" simulate "$@" --out "$outf" --force --quiet >>"$log" 2>&1 || rc=$?
  if [ "$rc" -ne 0 ]; then
    if [ "$may_stop" = 1 ] && [ "$rc" -eq 1 ] && [ -f "$outf.partial" ]; then
      mv "$outf.partial" "${outf%.h5}.stopped.h5"
      say "kept stopped run ${outf%.h5}.stopped.h5 ($*)"
    else
      tail -5 "$log" >&2
      die "lgi simulate $* failed (exit $rc)"
    fi
  fi
}

if [ "$mode" = quick ]; then
  book_dt=2e-3; top_dt=2e-3; save=10; repeats=1
  t1_tol=1e-6; t1_ref_tol=1e-11
  euler_tols="1e-6 1e-8"
else
  book_dt=1e-3; top_dt=5e-4; save=10; repeats=5
  t1_tol=1e-6; t1_ref_tol=1e-12
  euler_tols="1e-6 1e-8 1e-10 1e-12"
fi
lie_scheme=rkmk4

# ── trajectories: the book, the prism, the heavy tops ───────────────────────
mkdir -p "$data/traj"
for axis in 1 2 3; do
  for s in "$lie_scheme" exact; do
    simulate 0 "$data/traj/book_axis${axis}_$s.h5" --scene "$scenes/dzhanibekov_book_axis$axis.toml" \
      --scheme "$s" --dt "$book_dt" --save-every "$save"
  done
done
simulate 0 "$data/traj/prism_$lie_scheme.h5" --scene "$scenes/prism_edurev.toml" --scheme "$lie_scheme" \
  --dt 1e-2 --save-every 2
for case in 1 2 3 4 singular; do
  simulate 0 "$data/traj/top_${case}_$lie_scheme.h5" --scene "$scenes/heavy_top_trindade_$case.toml" \
    --scheme "$lie_scheme" --dt "$top_dt" --save-every "$save"
done
# Euler angles of the singular case: the singularity study's unguarded runs (below) when this
# lgi has it; else guarded lgi simulate runs (which stop where the chart is singular).
if ! has_sub singularity && has_scheme euler-zxz/dopri5; then
  for tol in $euler_tols; do
    simulate 1 "$data/traj/top_singular_euler_$tol.h5" --scene "$scenes/heavy_top_trindade_singular.toml" \
      --scheme euler-zxz/dopri5 --tol "$tol" --save-every 1
  done
elif ! has_sub singularity; then
  missing_note heavy_top_singular_baseline "This \\texttt{lgi} has neither \\texttt{singularity} nor the \\texttt{euler-zxz/dopri5} baseline: the Euler-angle curves are absent."
fi
say "trajectories done ($(( $(date +%s) - t_start )) s)"

# ── Table 1: CPU time at tolerance 1e-6 on Trindade cases 1-4 ───────────────
mkdir -p "$data/table1"
t1_schemes=""
for s in euler-zxz/dopri5 euler-zxz/rkf78 euler-zxz/bs euler-zxz/rosenbrock4 \
         rotvec/dopri5 rotvec/rkf78 rotvec/bs rotvec/rosenbrock4 \
         quat/dopri5 quat-normalized/dopri5 matrix/dopri5 rkmk-dp54; do
  has_scheme "$s" && t1_schemes="$t1_schemes $s"
done
table1_files=(); table1_refs=()
for case in 1 2 3 4; do
  sc="$scenes/heavy_top_trindade_$case.toml"
  simulate 0 "$data/table1/ref_$case.h5" --scene "$sc" --scheme rkmk-dp54 --tol "$t1_ref_tol" --save-every 1000000000
  table1_refs+=("$data/table1/ref_$case.h5")
  for s in $t1_schemes; do
    for rep in $(seq 1 "$repeats"); do
      f="$data/table1/$(tr '/@' '__' <<<"$s")_${case}_$rep.h5"
      simulate 1 "$f" --scene "$sc" --scheme "$s" --tol "$t1_tol" --save-every 1000000000
      [ -f "$f" ] && table1_files+=("$f") || table1_files+=("${f%.h5}.stopped.h5")
    done
  done
done
say "table 1 done ($(( $(date +%s) - t_start )) s)"

# ── work-precision (and convergence) ─────────────────────────────────────────
wp_files=()
if has_sub work-precision; then
  mkdir -p "$data/wp"
  fixed_common="rkmk4 cg4a cf4 rkmk3 simo-wong split-exact lgvi lgvi@yoshida4 lgvi@kahan-li6 lgvi@kahan-li8 split-exact@suzuki4 split-exact@kahan-li8 split-axes@kahan-li8 split-symmetric split-symmetric@kahan-li8 split-symmetric@bcm-processed6 split-symmetric@bcm-processed8 lgvi@bcm-processed8 rkmk-gauss4 quat/rk4 quat-normalized/rk4 matrix/rk4 rotvec/rk4"
  fixed_free="dmv dmv-pre4 dmv-pre6 dmv-pre8 dmv-pre10 dmv@kahan-li8"
  adaptive="rkmk-dp54 rkmk-verner65 rkmk-dop853 rkmk-verner87 rkmk-verner98 rkmk-cayley-verner87 rkmk-cayley-verner98 euler-zxz/dopri5 rotvec/dopri5 quat/dopri5 euler-zxz/rkf78 rotvec/rkf78 quat/rkf78"
  if [ "$mode" = quick ]; then
    wp_cases=("dzhanibekov_book_axis2|4|2e-3,1e-3,5e-4|1e-5,1e-8" "heavy_top_trindade_1|2|2e-3,1e-3,5e-4|1e-5,1e-8"
              "heavy_top_hlw|2|1e-2,5e-3|1e-6,1e-10")
  else
    wp_cases=("dzhanibekov_book_axis2|14|1e-2,5e-3,2e-3,1e-3,5e-4,2e-4,1e-4|1e-4,1e-6,1e-8,1e-10,1e-12"
              "heavy_top_trindade_1|10|4e-3,2e-3,1e-3,5e-4,2.5e-4,1.25e-4|1e-4,1e-6,1e-8,1e-10,1e-12"
              "kovalevskaya|20|2e-2,1e-2,5e-3,2e-3,1e-3,5e-4|1e-4,1e-6,1e-8,1e-10,1e-12"
              "heavy_top_hlw|10|1e-2,5e-3,2e-3,1e-3,5e-4,2.5e-4|1e-4,1e-6,1e-8,1e-10,1e-12")
  fi
  for spec in "${wp_cases[@]}"; do
    IFS='|' read -r scene t_end dts tols <<<"$spec"
    free=any; case "$scene" in dzhanibekov*|free_body*|prism*) free=free ;; esac
    list=$(filter_schemes "$free" $fixed_common $([ $free = free ] && echo $fixed_free) $adaptive)
    say "work-precision $scene: $list"
    "$lgi" work-precision --scene "$scenes/$scene.toml" --schemes "$list" --dt "$dts" --tol "$tols" \
      --t-end "$t_end" --repeat "$repeats" --out "$data/wp/$scene.h5" --force --quiet >>"$log" 2>&1 \
      || { tail -5 "$log" >&2; die "lgi work-precision on $scene failed"; }
    wp_files+=("$data/wp/$scene.h5")
  done
else
  for n in work_precision convergence; do
    missing_note "$n" "This \\texttt{lgi} has no \\texttt{work-precision} subcommand: the figure is absent."
  done
fi
say "work-precision done ($(( $(date +%s) - t_start )) s)"

# ── long-time ────────────────────────────────────────────────────────────────
lt_files=()
if has_sub long-time; then
  mkdir -p "$data/lt"
  . "$root/scripts/long_time_cases.sh"
  long_time_cases "$mode"
  for spec in "${lt_cases[@]}"; do
    IFS='|' read -r scene dt t_end schemes_lt <<<"$spec"
    for s in $schemes_lt; do
      has_scheme "$s" || { say "long-time: no scheme $s here, skipped"; continue; }
      f="$data/lt/${scene}_$(tr '/@' '__' <<<"$s").h5"
      "$lgi" long-time --scene "$scenes/$scene.toml" --scheme "$s" --dt "$dt" --t-end "$t_end" \
        --out "$f" --force --quiet >>"$log" 2>&1 \
        || { tail -5 "$log" >&2; die "lgi long-time $scene $s failed"; }
      lt_files+=("$f")
    done
  done
else
  missing_note long_time "This \\texttt{lgi} has no \\texttt{long-time} subcommand: the figure is absent."
fi
# Brouwer's law: dmv on the book, 10^6 steps (quick) or 10^8 (full), for the round-off figure.
roundoff_file=""
if has_sub long-time && has_scheme dmv; then
  if [ "$mode" = quick ]; then ro_t_end=1e4; else ro_t_end=1e6; fi
  roundoff_file="$data/lt/roundoff_dzhanibekov_book_axis2_dmv.h5"
  "$lgi" long-time --scene "$scenes/dzhanibekov_book_axis2.toml" --scheme dmv --dt 0.01 --t-end "$ro_t_end" \
    --out "$roundoff_file" --force --quiet >>"$log" 2>&1 || { tail -5 "$log" >&2; die "lgi long-time (round-off) failed"; }
else
  missing_note round_off "This \\texttt{lgi} has no \\texttt{long-time} or no \\texttt{dmv}: the round-off figure is absent."
fi
say "long-time done ($(( $(date +%s) - t_start )) s)"

# ── stress and singularity ───────────────────────────────────────────────────
quick_flag=""; [ "$mode" = quick ] && quick_flag="--quick"
stress_file=""
if has_sub stress; then
  "$lgi" stress $quick_flag --out "$data/stress.h5" --force --quiet >>"$log" 2>&1 \
    || { tail -5 "$log" >&2; die "lgi stress failed"; }
  stress_file="$data/stress.h5"
fi
singularity_file=""
singularity_sweep=()
if has_sub singularity; then
  # The study at the scenes' tolerance (table and figure), and, for the Euler angles of the
  # singular case at several tolerances (Trindade & Sampaio's Figures 7-10), at each of $euler_tols.
  "$lgi" singularity $quick_flag --out "$data/singularity.h5" --force --quiet >>"$log" 2>&1 \
    || { tail -5 "$log" >&2; die "lgi singularity failed"; }
  singularity_file="$data/singularity.h5"
  for tol in $euler_tols; do
    "$lgi" singularity $quick_flag --tol "$tol" --out "$data/singularity_tol$tol.h5" --force --quiet >>"$log" 2>&1 \
      || { tail -5 "$log" >&2; die "lgi singularity --tol $tol failed"; }
    singularity_sweep+=("$data/singularity_tol$tol.h5")
  done
else
  missing_note singularity "This \\texttt{lgi} has no \\texttt{singularity} subcommand: the figure is absent."
fi
say "experiments done ($(( $(date +%s) - t_start )) s)"

# ── figures (two at a time) and tables ───────────────────────────────────────
pids=()
plot() {  # plot SCRIPT ARGS...: in the background; waited for below
  "$PY" "$plots/$1" --out "$figs" "${@:2}" >>"$log" 2>&1 &
  pids+=("$!:$1")
  if [ "${#pids[@]}" -ge 2 ]; then wait_plots; fi
}
wait_plots() {
  local p
  for p in "${pids[@]}"; do
    wait "${p%%:*}" || { tail -15 "$log" >&2; die "plot script ${p#*:} failed"; }
  done
  pids=()
}
cd "$plots"
# Line styles (baselines dashed, compositions dash-dot) come from the schemes' facts in schemes.json.
plot dzhanibekov.py "$data"/traj/book_axis*.h5
plot ellipsoids.py "$data"/traj/book_axis*_"$lie_scheme".h5
plot heavy_top.py "$data"/traj/top_*.h5 ${singularity_sweep[@]+"${singularity_sweep[@]}"}
if [ "$mode" = quick ]; then frames=40; else frames=140; fi
plot animate.py --frames "$frames" "$data/traj/book_axis2_$lie_scheme.h5" "$data/traj/prism_$lie_scheme.h5"
[ ${#wp_files[@]} -gt 0 ] && plot work_precision.py --schemes-json "$gen/schemes.json" "${wp_files[@]}"
[ ${#lt_files[@]} -gt 0 ] && plot long_time.py --schemes-json "$gen/schemes.json" "${lt_files[@]}"
[ -n "$roundoff_file" ] && plot round_off.py "$roundoff_file"
[ -n "$singularity_file" ] && plot singularity.py --schemes-json "$gen/schemes.json" "$singularity_file"
wait_plots

# paper_section SCRIPT "SUBCOMMANDS" "FIGURES" "NOTES": one paper section's data, figures and numbers from
# scripts/SCRIPT, when this lgi has every subcommand it needs; else each figure and each generated .tex of NOTES
# says what is missing, and the status is 1 so that the caller writes the section's other placeholders.
paper_section() {
  local script="$1" subs="$2" figures="$3" texs="$4" s n
  local why="This \\texttt{lgi} lacks ${subs// /, }: no data."
  for s in $subs; do
    has_sub "$s" && continue
    for n in $figures; do missing_note "$n" "$why"; done
    for n in $texs; do printf '\\lginote{%s}\n' "$why" > "$gen/$n"; done
    return 1
  done
  "$root/scripts/$script" --lgi "$lgi" --data "$data" --figs "$figs" --gen "$gen" --mode "$mode" \
    >>"$log" 2>&1 || { tail -5 "$log" >&2; die "scripts/$script failed"; }
}

# ── the global dynamics of tops (paper/sections/tops.tex) ────────────────────
paper_section paper_atlas.sh "equilibria bifurcation poincare" "" \
  "atlas_equilibria.tex atlas_megno.tex atlas_commands.tex" || true
say "atlas done ($(( $(date +%s) - t_start )) s)"

# ── quantum tops (paper/sections/quantum.tex) ────────────────────────────────
paper_section paper_quantum.sh "quantum chaos-map" "quantum_levels_richter quantum_ebk quantum_compare" \
  "quantum_compare.tex quantum_commands.tex" || {
  echo '\multicolumn{6}{l}{no data: this \texttt{lgi} lacks quantum} \\' > "$gen/quantum_euler_ebk.tex"
  printf '\\newcommand{\\%s}{?}\n' QLagEbkErrors QLagEbkHbars QLagEbkRatios > "$gen/quantum_numbers.tex"
}
say "quantum done ($(( $(date +%s) - t_start )) s)"

# ── periodic orbits (paper/sections/periodic.tex) ───────────────────────────
paper_section paper_periodic.sh "periodic poincare" "periodic_period_l22 periodic_period_l3 poincare_section_l3" \
  "periodic_commands.tex" || {
  grep -o '\\Per[A-Z][A-Za-z]*' "$paper/sections/periodic.tex" | sort -u \
    | sed 's/.*/\\newcommand{&}{?}/' > "$gen/periodic_numbers.tex"
  echo '\multicolumn{9}{l}{no data: this \texttt{lgi} lacks periodic or poincare} \\' > "$gen/periodic_families.tex"
}
say "periodic done ($(( $(date +%s) - t_start )) s)"

# ── three degrees of freedom (paper/sections/three_dof.tex) ──────────────────
paper_section paper_3dof.sh "chaos-map frequencies indicators" \
  "three_dof_maps three_dof_frequency_map three_dof_gali" "three_dof_commands.tex" || {
  grep -o '\\Tdof[A-Za-z]*' "$paper/sections/three_dof.tex" | sort -u \
    | sed 's/.*/\\newcommand{&}{?}/' > "$gen/three_dof_numbers.tex"
}
say "three degrees of freedom done ($(( $(date +%s) - t_start )) s)"

# ── benchmarks: ns per step and ratios to quat/rk4 (Google Benchmark, one run) ─
bench="$(dirname "$lgi")/lgi_bench"
rm -f "$gen/benchmarks.tex"
if [ -x "$bench" ]; then
  if [ "$mode" = quick ]; then bench_min=0.005 bench_procs=1; else bench_min=0.1 bench_procs=5; fi
  "$PY" "$root/scripts/benchmark_ratios.py" --bench "$bench" --min-time "$bench_min" --processes "$bench_procs" \
    --tex "$gen/benchmarks.tex" --skip-long-run \
    >>"$log" 2>&1 || { tail -5 "$log" >&2; die "scripts/benchmark_ratios.py failed"; }
else
  missing_note benchmarks "No \\texttt{lgi\\_bench} next to this \\texttt{lgi} (configure with LGI\\_BUILD\\_BENCHMARKS=ON): no cost-per-step table."
fi
say "benchmarks done ($(( $(date +%s) - t_start )) s)"

"$PY" "$plots/make_tables.py" --out "$gen" --schemes-json "$gen/schemes.json" --scenes-dir "$scenes" \
  --table1 "${table1_files[@]}" --table1-reference "${table1_refs[@]}" \
  ${wp_files[@]+--wp "${wp_files[@]}"} ${lt_files[@]+--lt "${lt_files[@]}"} \
  ${stress_file:+--stress "$stress_file"} ${singularity_file:+--singularity "$singularity_file"} \
  --mode "$mode" --lgi "$lgi" >>"$log" 2>&1 || { tail -15 "$log" >&2; die "make_tables.py failed"; }
t_data=$(( $(date +%s) - t_start ))
printf '\\renewcommand{\\DataWallSeconds}{%s}\n' "$t_data" >> "$gen/machine.tex"
say "figures and tables done (${t_data} s)"

# ── the PDF ──────────────────────────────────────────────────────────────────
# lgi.tex reads build/figures/ and generated/ relative to the folder LaTeX runs in:
# paper/ by default; with --out, DIR/tex, which links paper/'s sources and maps
# build -> DIR and generated -> DIR/generated (so nothing is written in paper/).
if [ -n "$out_arg" ]; then
  texdir="$out/tex"
  rm -rf "$texdir"
  mkdir -p "$texdir"
  for f in "$paper"/*; do
    case "$(basename "$f")" in build|generated) ;; *) ln -s "$f" "$texdir/" ;; esac
  done
  ln -s "$out" "$texdir/build"
  ln -s "$gen" "$texdir/generated"
else
  texdir="$paper"
fi
cd "$texdir"
latexmk -pdf -interaction=nonstopmode -halt-on-error -file-line-error -outdir="$out" lgi.tex >>"$log" 2>&1 \
  || { grep -A3 -E '^(!|.*:[0-9]+:)' "$out/lgi.log" | head -30 >&2; die "latexmk failed (see $out/lgi.log)"; }
figures=$(sed -n 's/^LGI-FIGURES: \([0-9]*\).*/\1/p' "$out/lgi.log" | tail -1)
missing=$(sed -n 's/^LGI-MISSING: \([0-9]*\).*/\1/p' "$out/lgi.log" | tail -1)
# Layout (CTest paper_quick wants both zero): lines that run past the margin by
# 5 pt or more (TeX's "Overfull \hbox"), and floats taller than a page.
wide=$(grep -cE '^Overfull \\hbox \(([5-9]|[1-9][0-9]+)\.[0-9]+pt too wide' "$out/lgi.log" || true)
tall=$(grep -c 'Float too large' "$out/lgi.log" || true)
say "layout: $wide lines past the margin by 5 pt or more, $tall floats taller than the page"
say "wrote $out/lgi.pdf: ${figures:-?} figures, ${missing:-?} notes about missing data; total $(( $(date +%s) - t_start )) s"
