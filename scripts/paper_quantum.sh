#!/usr/bin/env bash
# The data, figures and tables of the paper's section "Quantum tops"
# (paper/sections/quantum.tex): the spectrum of Richter's top against hbar, EBK
# against exact levels (Lagrange and Euler tops) and the spacing statistics of
# four tops beside their classical chaotic fraction (experiments/QUANTUM.md).
# Called by scripts/build_paper.sh; every number comes from lgi runs made here.
#
# Usage: scripts/paper_quantum.sh --lgi PATH --data DIR --figs DIR --gen DIR --mode quick|full
# Writes DIR(data)/quantum/*.h5, figures quantum_levels_richter, quantum_ebk and
# quantum_compare in --figs, and --gen/quantum_compare.tex, --gen/quantum_euler_ebk.tex,
# --gen/quantum_numbers.tex, --gen/quantum_commands.tex.
set -euo pipefail

section=quantum help_lines='2,11p'
source "$(dirname "$0")/paper_section.sh" "$@"
q="$out"

# ── the spectrum of Richter's top against hbar (m = 0, the lowest 12 levels) ─
if [ "$mode" = quick ]; then hbars="0.2:24 0.1:30 0.05:40"; else hbars="0.2:24 0.14:28 0.1:30 0.07:36 0.05:40 0.035:50 0.025:60"; fi
level_files=()
for hj in $hbars; do
  h="${hj%%:*}" j="${hj##*:}"
  run quantum --scene "$scenes/general_top_richter.toml" --hbar "$h" --m 0 --jmax "$j" --levels 12 \
    --out "$q/richter_hbar_$h.h5"
  level_files+=("$q/richter_hbar_$h.h5")
done

# ── EBK: the Lagrange top (three hbar) and the Euler top (|L| = 1, hbar = 1/(j + 1/2)) ─
ebk_files=()
for hj in 0.1:30 0.05:40 0.025:60; do
  h="${hj%%:*}" j="${hj##*:}"
  run quantum --scene "$scenes/lagrange_top_cigar.toml" --hbar "$h" --m 1 --jmax "$j" --levels 10 --ebk \
    --out "$q/ebk_lagrange_$h.h5"
  ebk_files+=("$q/ebk_lagrange_$h.h5")
done
euler_files=()
for j in 10 20 40 80; do
  h=$("$PY" -c "print(repr(1 / ($j + 0.5)))")
  run quantum --scene "$scenes/free_body_hlw.toml" --hbar "$h" --m "$j" --jmax "$j" --ebk --out "$q/ebk_euler_$j.h5"
  euler_files+=("$q/ebk_euler_$j.h5")
done

# ── four tops at l = 1, h in [1, 2]: quantum statistics and the classical chaotic fraction ─
if [ "$mode" = quick ]; then
  hbar=0.2 m=5 jq=26 lv_r=130 lv_k=160 lv_l=80 jf=16 ics=16 t_end=200
else
  hbar=0.1 m=10 jq=46 lv_r=500 lv_k=600 lv_l=300 jf=30 ics=100 t_end=400
fi
window=1:2
cases=()
for spec in "Euler:free_body_hlw" "Lagrange:lagrange_top_cigar" "Kovalevskaya:kovalevskaya" "Richter:general_top_richter"; do
  label="${spec%%:*}" stem="${spec##*:}"
  case "$stem" in
    free_body_hlw) qargs=(--jmax "$jf") ;;
    lagrange_top_cigar) qargs=(--jmax "$jq" --levels "$lv_l") ;;
    kovalevskaya) qargs=(--jmax "$jq" --levels "$lv_k") ;;
    *) qargs=(--jmax "$jq" --levels "$lv_r") ;;
  esac
  run quantum --scene "$scenes/$stem.toml" --hbar "$hbar" --m "$m" "${qargs[@]}" --statistics \
    --energy-window "$window" --out "$q/stat_$stem.h5"
  run chaos-map --scene "$scenes/$stem.toml" --l-range 1:1:1 --h-range 1:2:5 --ics "$ics" --t-end "$t_end" \
    --threads 2 --out "$q/chaos_$stem.h5"
  cases+=(--case "$label" "$q/stat_$stem.h5" "$q/chaos_$stem.h5")
done

# ── figures and tables ───────────────────────────────────────────────────────
"$PY" "$plots/quantum_levels.py" --out "$figs" --name quantum_levels_richter "${level_files[@]}" \
  || die "quantum_levels.py failed"
"$PY" "$plots/quantum.py" --out "$figs" --name quantum_ebk "${ebk_files[@]}" "${euler_files[@]}" || die "quantum.py failed"
"$PY" "$plots/quantum_compare.py" --out "$figs" --tex "$gen/quantum_compare.tex" "${cases[@]}" \
  || die "quantum_compare.py failed"
"$PY" - "$plots" "$gen" "$commands" "${ebk_files[@]}" -- "${euler_files[@]}" <<'EOF' || die "the quantum tables failed"
# quantum_euler_ebk.tex (rows: j, hbar, the largest relative error in the two windows, ratios),
# quantum_numbers.tex (macros for the text) and quantum_commands.tex (the runs, verbatim).
import sys
import h5py
import numpy as np

plots, gen, commands = sys.argv[1], sys.argv[2], sys.argv[3]
rest = sys.argv[4:]
cut = rest.index("--")
lagrange, euler = rest[:cut], rest[cut + 1:]


def hbar(path):
    with h5py.File(path, "r") as f:
        return float(f["parameters"].attrs["hbar"])


def ebk(path):
    with h5py.File(path, "r") as f:
        return {k: f["ebk"][k][()] for k in f["ebk"]}


lag = [(hbar(p), float(np.max(np.abs(ebk(p)["difference"])))) for p in sorted(lagrange, key=hbar, reverse=True)]
rows, prev = [], None
for p in sorted(euler, key=hbar, reverse=True):
    t, h = ebk(p), hbar(p)
    e, d = t["energy_exact"], t["difference"]
    errs = []
    for lo, hi in ((0.25, 0.42), (0.58, 0.75)):  # E/|L|^2, |L| = 1: about J_max, about J_min
        w = (e >= lo) & (e <= hi) & np.isfinite(d)
        errs.append(float(np.max(np.abs(d[w] / e[w]))))
    ratio = "" if prev is None else f"{prev[1][0] / errs[0]:.2f}, {prev[1][1] / errs[1]:.2f} & {(prev[0] / h) ** 2:.2f}"
    rows.append(f"{int(t['j'][0])} & {h:.4f} & {errs[0]:.2e} & {errs[1]:.2e} & "
                + (ratio if ratio else "& ") + " \\\\")
    prev = (h, errs)
open(f"{gen}/quantum_euler_ebk.tex", "w").write("\n".join(rows) + "\n")
with open(f"{gen}/quantum_numbers.tex", "w") as f:
    f.write(f"\\newcommand{{\\QLagEbkErrors}}{{{', '.join(f'{x:.2e}' for _, x in lag)}}}\n")
    f.write(f"\\newcommand{{\\QLagEbkHbars}}{{{', '.join(f'{h:g}' for h, _ in lag)}}}\n")
    ratios = [lag[i][1] / lag[i + 1][1] for i in range(len(lag) - 1)]
    f.write(f"\\newcommand{{\\QLagEbkRatios}}{{{', '.join(f'{r:.2f}' for r in ratios)}}}\n")
sys.path.insert(0, plots)
from atlas_tables import commands_block  # the same wrapped, pasteable block as the atlas section
open(f"{gen}/quantum_commands.tex", "w").write(commands_block(commands))
EOF
