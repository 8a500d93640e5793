#!/usr/bin/env bash
# The data, figures and tables of the paper's section "The global dynamics of
# tops" (paper/sections/tops.tex): relative equilibria, bifurcation diagrams,
# Poincaré sections and chaos indicators of the heavy top (seed 003). Called by
# scripts/build_paper.sh; every number comes from lgi runs made here.
#
# Usage: scripts/paper_atlas.sh --lgi PATH --data DIR --figs DIR --gen DIR --mode quick|full
# Writes DIR(data)/atlas/*.h5, figures bifurcation_*, appelrot_*, poincare_*, region_*,
# poisson_sphere_potentials, chaos_map_*, actions_integrable and poincare_section_cardan_euler_* in --figs,
# and --gen/atlas_equilibria.tex, --gen/atlas_megno.tex, --gen/atlas_cardan.tex, --gen/atlas_cardan_megno.tex,
# --gen/atlas_commands.tex.
set -euo pipefail

section=atlas help_lines='2,10p'
source "$(dirname "$0")/paper_section.sh" "$@"
atlas="$out"
mkdir -p "$atlas/equilibria" "$atlas/bifurcation" "$atlas/poincare" "$figs" "$gen"

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

# ── accessible regions, energy-surface topologies, the Appelrot diagram, the chaos map ─
mkdir -p "$atlas/region" "$atlas/chaos"
run region --scene "$scenes/free_body_hlw.toml" --l 1 --h 0.6 --out "$atlas/region/euler.h5"
run region --scene "$scenes/lagrange_top_oblate.toml" --l 1 --h 1 --out "$atlas/region/lagrange.h5"
run region --scene "$scenes/general_top_richter.toml" --l 2 --h 2.2 --out "$atlas/region/general.h5"
if [ "$mode" = quick ]; then cells=41; else cells=121; fi
run region --scene "$scenes/lagrange_top_oblate.toml" --cells --l-range "0:3:$cells" --h-range "-1.2:3:$cells" \
  --out "$atlas/region/lagrange_top_oblate.h5"
run bifurcation --scene "$scenes/kovalevskaya.toml" --appelrot 0,1,2 --out "$atlas/bifurcation/kovalevskaya_appelrot.h5"
if [ "$mode" = quick ]; then
  chaos_grid=(--l-range 0:3:5 --h-range -0.5:4:6 --ics 6 --t-end 150)
else
  chaos_grid=(--l-range 0:3:13 --h-range -0.5:4:19 --ics 20 --t-end 400)
fi
run chaos-map --scene "$scenes/general_top_richter.toml" "${chaos_grid[@]}" --threads 2 \
  --out "$atlas/chaos/general_top_richter.h5"

# ── the top in a Cardan suspension on T^3 (docs/cardan.md) and the actions of the integrable tops ─
mkdir -p "$atlas/cardan" "$atlas/actions"
cardan_summary="$atlas/cardan/summary.txt"
: > "$cardan_summary"
for stem in cardan_lagrange_upright cardan_lagrange_horizontal cardan_trindade_1_massless; do
  for scheme in cardan-midpoint cardan-dg cardan-rk4; do
    args=(simulate --scene "$scenes/$stem.toml" --scheme "$scheme" --out "$atlas/cardan/${stem}_$scheme.h5")
    echo "lgi ${args[*]}" | sed "s|$root/||g; s|$atlas/||g" >> "$commands"
    line=$("$lgi" "${args[@]}" --force) || die "lgi simulate failed: lgi ${args[*]}"
    echo "scene=$stem $line" >> "$cardan_summary"
  done
done
# seed 003's six examples ("Rigid bodies in T^3"): MEGNO of orbits on the level (p1, h) of each
# scene's initial state, and the T^3 sections (docs/cardan.md section 9) of the Euler pair.
if [ "$mode" = quick ]; then c_ics=3 c_t=100 s_ics=10 s_t=150; else c_ics=16 c_t=600 s_ics=40 s_t=300; fi
cardan_secs=()
for stem in cardan_lagrange_upright cardan_lagrange_horizontal cardan_euler_symmetric_up cardan_euler_tilted \
            cardan_general_horizontal cardan_general_asymmetric_up; do
  case "$stem" in cardan_lagrange_*) cdt=0.001 ;; *) cdt=0.005 ;; esac
  "$lgi" simulate --scene "$scenes/$stem.toml" --scheme cardan-rk4 --t-end "$cdt" --dt "$cdt" \
    --out "$atlas/cardan/level_$stem.h5" --force --quiet || die "lgi simulate failed on $stem"
  read -r cl ch < <("$PY" -c 'import sys, h5py
o = h5py.File(sys.argv[1], "r")["observables"]
print(repr(float(o["cardan_momentum_1"]["value"][0])), repr(float(o["energy"]["value"][0])))' \
    "$atlas/cardan/level_$stem.h5") || die "no level of $stem"
  run poincare --scene "$scenes/$stem.toml" --l "$cl" --h "$ch" --ics "$c_ics" --t-end "$c_t" --dt "$cdt" --megno \
    --lyapunov --out "$atlas/cardan/megno_$stem.h5"
  cardan_secs+=("$atlas/cardan/megno_$stem.h5")
done
# each at the level of its scene's initial state, to 3 digits (docs/cardan.md §9.3)
for level in "cardan_euler_symmetric_up 2.85 6.96" "cardan_euler_tilted 2.51 6.43"; do
  read -r stem sl sh <<< "$level"
  run poincare --scene "$scenes/$stem.toml" --l "$sl" --h "$sh" --ics "$s_ics" --t-end "$s_t" --dt 0.005 --megno \
    --out "$atlas/cardan/section_$stem.h5"
done
run actions --scene "$scenes/lagrange_top_cigar.toml" --h 2 --grid 41 --out "$atlas/actions/lagrange_top_cigar.h5"
run actions --scene "$scenes/free_body_hlw.toml" --h 1 --grid 41 --out "$atlas/actions/free_body_hlw.h5"
# The Kovalevskaya top has no closed form here: its tori at h = 2 found from the flow (docs/actions.md §3).
if [ "$mode" = quick ]; then kl=-1,-0.5,0,0.5,1 kt=4; else kl=-1.5,-1.25,-1,-0.75,-0.5,-0.25,0,0.25,0.5,0.75,1,1.25,1.5 kt=12; fi
run actions --scene "$scenes/kovalevskaya.toml" --h 2 --l "$kl" --tori "$kt" --out "$atlas/actions/kovalevskaya.h5"

# ── figures and tables ───────────────────────────────────────────────────────
"$PY" "$plots/actions.py" --out "$figs" --name actions_integrable "$atlas/actions/lagrange_top_cigar.h5" \
  "$atlas/actions/free_body_hlw.h5" "$atlas/actions/kovalevskaya.h5" || die "actions.py failed"
"$PY" "$plots/poincare.py" --out "$figs" --colour megno "$atlas/cardan/section_cardan_euler_symmetric_up.h5" \
  "$atlas/cardan/section_cardan_euler_tilted.h5" || die "poincare.py (Cardan) failed"
"$PY" "$plots/region.py" --out "$figs" --combine poisson_sphere_potentials "$atlas/region/euler.h5" \
  "$atlas/region/lagrange.h5" "$atlas/region/general.h5" || die "region.py failed"
"$PY" "$plots/region.py" --out "$figs" "$atlas/region/lagrange_top_oblate.h5" || die "region.py --cells failed"
"$PY" "$plots/bifurcation.py" --out "$figs" "$atlas/bifurcation/kovalevskaya_appelrot.h5" \
  || die "bifurcation.py --appelrot failed"
"$PY" "$plots/chaos_map.py" --out "$figs" --branches "$atlas/bifurcation/general_top_richter.h5" \
  "$atlas/chaos/general_top_richter.h5" || die "chaos_map.py failed"
"$PY" "$plots/bifurcation.py" --out "$figs" --l-nonneg "${bif_files[@]}" || die "bifurcation.py failed"
"$PY" "$plots/poincare.py" --out "$figs" "${sec_files[@]}" || die "poincare.py failed"
"$PY" "$plots/poincare.py" --out "$figs/megno" --colour megno "$atlas/poincare/general_top_richter.h5" \
  || die "poincare.py --colour megno failed"
mv "$figs/megno/poincare_general_top_richter.pdf" "$figs/poincare_megno_general_top_richter.pdf"
mv "$figs/megno/poincare_general_top_richter.png" "$figs/poincare_megno_general_top_richter.png"
rmdir "$figs/megno" 2>/dev/null || true
"$PY" "$plots/atlas_tables.py" --out "$gen" --equilibria "${eq_files[@]}" --sections "${sec_files[@]}" \
  --commands "$commands" --cardan "$cardan_summary" --cardan-sections "${cardan_secs[@]}" \
  || die "atlas_tables.py failed"
