#!/usr/bin/env bash
# The data, figures and tables of the paper's section "The global dynamics of
# tops" (paper/sections/tops.tex): relative equilibria, bifurcation diagrams,
# Poincaré sections and chaos indicators of the heavy top (seed 003). Called by
# scripts/build_paper.sh; every number comes from lgi runs made here.
#
# Usage: scripts/paper_atlas.sh --lgi PATH --data DIR --figs DIR --gen DIR --mode quick|full
# Writes DIR(data)/atlas/*.h5, figures bifurcation_*, poincare_* in --figs, and
# --gen/atlas_equilibria.tex, --gen/atlas_megno.tex, --gen/atlas_commands.tex.
set -euo pipefail

root="$(cd "$(dirname "$0")/.." && pwd)"
lgi="" data="" figs="" gen="" mode=quick
while [ $# -gt 0 ]; do
  case "$1" in
    --lgi) lgi="$2"; shift ;;
    --data) data="$2"; shift ;;
    --figs) figs="$2"; shift ;;
    --gen) gen="$2"; shift ;;
    --mode) mode="$2"; shift ;;
    -h|--help) sed -n '2,10p' "$0"; exit 0 ;;
    *) echo "paper_atlas: unknown argument '$1' (see --help)" >&2; exit 2 ;;
  esac
  shift
done
for v in lgi data figs gen; do
  [ -n "${!v}" ] || { echo "paper_atlas: --$v is required" >&2; exit 2; }
done
case "$mode" in quick|full) ;; *) echo "paper_atlas: --mode must be quick or full" >&2; exit 2 ;; esac
die() { echo "paper_atlas: $*" >&2; exit 1; }
PY=/usr/bin/python3
plots="$root/scripts/plots"
scenes="$root/experiments/scenes"
atlas="$data/atlas"
mkdir -p "$atlas/equilibria" "$atlas/bifurcation" "$atlas/poincare" "$figs" "$gen"
commands="$gen/atlas_commands.txt"
: > "$commands"
run() {  # run lgi with ARGS, recording the command line (with paths relative to the repository)
  echo "lgi $*" | sed "s|$root/||g; s|$atlas/||g; s| --force --quiet||" >> "$commands"
  "$lgi" "$@" --force --quiet || die "lgi $1 failed: lgi $*"
}

# Scenes of the seed's slides that are not shipped scenes: written here from shipped ones.
# "Examples" (s = (1, 0, 0)): the non-integrable partner of the Kovalevskaya top, Richter's
# moments A = (1, 1.5, 2) with the centre of gravity on the first axis.
sed -e 's/^center_of_mass = .*/center_of_mass = [1.0, 0.0, 0.0]/' \
    -e 's/^name = .*/name = "Heavy top A = (1, 1.5, 2), s = (1, 0, 0)"/' \
  "$scenes/general_top_richter.toml" > "$atlas/richter_s100.toml"
# A Lagrange top: A = (1, 1, 2), s on the symmetry axis (the closed-form overlay of bifurcation.py).
sed -e 's/^inertia = .*/inertia = [1.0, 1.0, 2.0]/' \
    -e 's/^center_of_mass = .*/center_of_mass = [0.0, 0.0, 1.0]/' \
    -e 's/^name = .*/name = "Lagrange top A = (1, 1, 2), s = (0, 0, 1)"/' \
  "$scenes/general_top_richter.toml" > "$atlas/lagrange.toml"

# ── relative equilibria and bifurcation diagrams ────────────────────────────
eq_files=()
for l in 0 0.5 1 2 3; do
  run equilibria --scene "$scenes/general_top_richter.toml" --l "$l" --out "$atlas/equilibria/richter_l$l.h5"
  eq_files+=("$atlas/equilibria/richter_l$l.h5")
done
bif_files=()
for sc in "$scenes/general_top_richter.toml" "$atlas/richter_s100.toml" "$atlas/lagrange.toml" \
          "$scenes/kovalevskaya.toml"; do
  stem="$(basename "${sc%.toml}")"
  run bifurcation --scene "$sc" --out "$atlas/bifurcation/$stem.h5"
  bif_files+=("$atlas/bifurcation/$stem.h5")
done

# ── Poincaré sections with MEGNO (l = 1, h = 2: above every equilibrium's energy but one) ─
if [ "$mode" = quick ]; then ics=24; t_end=300; else ics=200; t_end=2000; fi
sec_files=()
for sc in "$scenes/kovalevskaya.toml" "$atlas/richter_s100.toml" "$scenes/general_top_richter.toml"; do
  stem="$(basename "${sc%.toml}")"
  run poincare --scene "$sc" --l 1 --h 2 --ics "$ics" --t-end "$t_end" --megno --threads 2 \
    --out "$atlas/poincare/$stem.h5"
  sec_files+=("$atlas/poincare/$stem.h5")
done

# ── figures and tables ───────────────────────────────────────────────────────
"$PY" "$plots/bifurcation.py" --out "$figs" "${bif_files[@]}" || die "bifurcation.py failed"
"$PY" "$plots/poincare.py" --out "$figs" "${sec_files[@]}" || die "poincare.py failed"
"$PY" "$plots/poincare.py" --out "$figs/megno" --colour megno "$atlas/poincare/general_top_richter.h5" \
  || die "poincare.py --colour megno failed"
mv "$figs/megno/poincare_general_top_richter.pdf" "$figs/poincare_megno_general_top_richter.pdf"
mv "$figs/megno/poincare_general_top_richter.png" "$figs/poincare_megno_general_top_richter.png"
rmdir "$figs/megno" 2>/dev/null || true
"$PY" "$plots/atlas_tables.py" --out "$gen" --equilibria "${eq_files[@]}" --sections "${sec_files[@]}" \
  --commands "$commands" || die "atlas_tables.py failed"
