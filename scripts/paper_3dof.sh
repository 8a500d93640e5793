#!/usr/bin/env bash
# The data, figures and numbers of the paper's section "Three degrees of freedom"
# (paper/sections/three_dof.tex): tilt-energy chaos maps of the Lagrange, Euler and general
# bodies in a Cardan suspension, a frequency map of one energy level with its resonance lines,
# and GALI of a 3-torus, a 2-torus and a chaotic orbit (experiments/CHAOS_MAP.md,
# FREQUENCIES.md, INDICATORS.md). Called by scripts/build_paper.sh; every number comes from
# the lgi runs made here.
#
# Usage: scripts/paper_3dof.sh --lgi PATH --data DIR --figs DIR --gen DIR --mode quick|full
# Writes DIR(data)/three_dof/*, figures three_dof_maps, three_dof_frequency_map and
# three_dof_gali in --figs, and --gen/three_dof_numbers.tex, --gen/three_dof_commands.tex.
set -euo pipefail

section=three_dof help_lines='2,11p'
source "$(dirname "$0")/paper_section.sh" "$@"
o="$out"
half_pi=1.5707963267948966
with_tilt() {  # with_tilt SCENE TILT OUT: the scene with its [suspension] tilt replaced
  sed "s/^tilt = .*/tilt = $2/" "$1" > "$3"
  grep -q "^tilt = $2\$" "$3" || die "could not set the tilt of $1"
}

# ── (a) chaos maps over (frame tilt, h): Lagrange, Euler (body tilted in the gimbal), general ─
if [ "$mode" = quick ]; then n=3 ics=2 tl=20 tg=20 te=20; else n=8 ics=6 tl=100 tg=200 te=200; fi
run chaos-map --scene "$scenes/cardan_lagrange_upright.toml" --vary "suspension.tilt=0:$half_pi:$n" \
  --h-range "-40:200:$n" --ics "$ics" --t-end "$tl" --dt 0.002 --threads 2 --out "$o/map_lagrange.h5"
run chaos-map --scene "$scenes/cardan_euler_tilted.toml" --vary "suspension.tilt=0:$half_pi:$n" \
  --h-range "0.5:8:$n" --ics "$ics" --t-end "$te" --dt 0.01 --threads 2 --out "$o/map_euler.h5"
run chaos-map --scene "$scenes/cardan_general_asymmetric_up.toml" --vary "suspension.tilt=0:$half_pi:$n" \
  --h-range "-0.75:3:$n" --ics "$ics" --t-end "$tg" --dt 0.005 --threads 2 --out "$o/map_general.h5"

# ── (b) a frequency map: the Lagrange top, frame tilted by 0.05 rad, at h = 400 ──────────
# The family: q = (0, theta, 0), rates along (a, 0, 1) scaled to H = h (scripts/plots/cardan_family.py);
# lgi simulate with unit rates at each theta gives M(q) and U(q).
if [ "$mode" = quick ]; then nth=5 nra=5 tf=20; else nth=28 nra=28 tf=200; fi
fm_tilt=0.05 fm_h=400
with_tilt "$scenes/cardan_lagrange_upright.toml" "$fm_tilt" "$o/lagrange_tilt.toml"
"$PY" "$plots/cardan_family.py" probes --scene "$o/lagrange_tilt.toml" --theta "0.2:1.4:$nth" --dir "$o/probes" \
  || die "cardan_family.py probes failed"
for f in "$o"/probes/probe_*.toml; do
  "$lgi" simulate --scene "$f" --scheme cardan-rk4 --t-end 0.001 --dt 0.001 --out "${f%.toml}.h5" --force --quiet \
    || die "lgi simulate $f failed"
done
echo "lgi simulate --scene probes/probe_I_K.toml --scheme cardan-rk4 --t-end 0.001 --dt 0.001 --out probes/probe_I_K.h5  # each of $((3 * nth)) probes" >> "$commands"
"$PY" "$plots/cardan_family.py" states --probes "$o/probes" --h "$fm_h" --rate-ratio=-0.3:0.3:"$nra" \
  --out "$o/family.h5" > "$o/family.log" || die "cardan_family.py states failed"
run frequencies --scene "$o/lagrange_tilt.toml" --state-file "$o/family.h5" --t-end "$tf" --dt 0.002 \
  --output-dt 0.01 --window-order 2 --terms 3 --observable sin_cardan_angle_1,cardan_angle_2,sin_cardan_angle_3 \
  --threads 2 --out "$o/frequency_map.h5"

# ── (c) GALI: a 3-torus, a 2-torus (steady precession) and a chaotic orbit ─────────────
if [ "$mode" = quick ]; then tt=50 tc=40; else tt=2000 tc=100; fi
"$PY" "$plots/steady_precession.py" --lgi "$lgi" --scene "$scenes/cardan_lagrange_upright.toml" \
  --theta 0.3490658503988659 --spin 50 --root fast --out "$o/steady_precession.toml" > "$o/steady_precession.log" \
  || die "steady_precession.py failed"
echo "python3 scripts/plots/steady_precession.py --lgi lgi --scene experiments/scenes/cardan_lagrange_upright.toml --theta 0.3490658503988659 --spin 50 --root fast --out steady_precession.toml" >> "$commands"
run indicators --scene "$scenes/cardan_lagrange_upright.toml" --t-end "$tt" --dt 0.005 --gali --out "$o/gali_torus3.h5"
run indicators --scene "$o/steady_precession.toml" --t-end "$tt" --dt 0.005 --gali --out "$o/gali_torus2.h5"
run frequencies --scene "$o/steady_precession.toml" --t-end 100 --dt 0.002 --output-dt 0.01 --window-order 2 \
  --terms 2 --observable sin_cardan_angle_1,cardan_angle_2,sin_cardan_angle_3 --out "$o/steady_precession_freq.h5"
run indicators --scene "$scenes/cardan_general_horizontal.toml" --t-end "$tc" --gali --gali-spacing linear \
  --spectrum --out "$o/gali_chaos.h5"

# ── figures and numbers ─────────────────────────────────────────────────────────────────
"$PY" "$plots/cardan_chaos_maps.py" --out "$figs" --name three_dof_maps --title "Lagrange body" \
  --title "Euler body, axis tilted 0.5 rad" --title "general body" \
  "$o/map_lagrange.h5" "$o/map_euler.h5" "$o/map_general.h5" || die "cardan_chaos_maps.py failed"
"$PY" "$plots/frequency_map.py" --out "$figs" --name three_dof_frequency_map --family "$o/family.h5" \
  "$o/frequency_map.h5" > "$o/frequency_map.log" || die "frequency_map.py failed"
"$PY" "$plots/gali_tori.py" --out "$figs" --name three_dof_gali --torus3 "$o/gali_torus3.h5" \
  --torus2 "$o/gali_torus2.h5" --chaos "$o/gali_chaos.h5" --json "$o/gali.json" || die "gali_tori.py failed"
"$PY" "$plots/three_dof_numbers.py" --data "$o" --commands "$commands" --gen "$gen" --tilt "$fm_tilt" \
  || die "three_dof_numbers.py failed"
