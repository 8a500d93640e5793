#!/usr/bin/env bash
# The data, figures and numbers of the paper's section "Periodic orbits"
# (paper/sections/periodic.tex): the families born at the stable relative
# equilibria of Richter's top at l = 2.2 and 3 with their stability, and a
# Poincaré section at l = 3 through the fold pair of one family (an elliptic
# and a hyperbolic orbit) with the manifolds of the hyperbolic one
# (experiments/PERIODIC.md). Called by scripts/build_paper.sh; every number
# comes from lgi runs made here.
#
# Usage: scripts/paper_periodic.sh --lgi PATH --data DIR --figs DIR --gen DIR --mode quick|full
# Writes DIR(data)/periodic/*.h5, figures periodic_period_l22, periodic_period_l3 and
# poincare_section_l3 in --figs, and --gen/periodic_numbers.tex, --gen/periodic_families.tex
# (the rows of the families' table), --gen/periodic_commands.tex.
# Time (2026-12-07, nice 19 on the project's shared 2-core machine): full mode 227 s CPU (the families
# at l = 3 are 3/4 of it), 9-10 min wall at load 5-7 and 34 min at load 10-15; quick mode 22 s CPU.
set -euo pipefail

section=periodic help_lines='2,12p'
source "$(dirname "$0")/paper_section.sh" "$@"
p="$out"
scene="$scenes/general_top_richter.toml"

# ── the families at l = 2.2 and 3 ───────────────────────────────────────────
# l = 3 needs 7 steps of 0.06 for the family of the equilibrium at h = 5.32 to pass its fold.
# The manifolds start at 1e-3 |x0| and are integrated for `periods` periods (|lambda|^periods
# times further out) with steps of 0.01 (sixth order: the orbits' points agree to about 1e-10).
if [ "$mode" = quick ]; then
  f22=(--steps 2 --h-step 0.04 --no-branch-switching --dt 0.005) f3=(--steps 7 --h-step 0.06 --no-branch-switching --dt 0.005)
  t_end=150 points=20 periods=8
else
  f22=(--steps 16 --h-step 0.02) f3=(--steps 24 --h-step 0.03)
  t_end=600 points=60 periods=10
fi
run periodic --scene "$scene" --l 2.2 --from-equilibria "${f22[@]}" --out "$p/l22.h5"
run periodic --scene "$scene" --l 3 --from-equilibria "${f3[@]}" --out "$p/l3.h5"

# ── the section through a fold pair at l = 3 ────────────────────────────────
# The fold pair: of every fold with elliptic orbits before it on its family, the hyperbolic orbit
# past it (up to the family's next fold) with 2 < tr P <= 3 nearest tr P = 2.5 gives h* (full mode
# also finds folds near the saddle-centre at h = 2.50, among orbits far more unstable, whose
# elliptic partners are small islands); the elliptic orbit at h* before the fold is interpolated
# between its two neighbours; their first crossings of Richter's section are the seeds
# (phi,theta,sheet) of lgi periodic at h*. The section's orbits start on rings about the elliptic
# orbit's crossing and beside the hyperbolic one's.
pick=$("$PY" - "$plots" "$p/l3.h5" "$p/section_seeds.csv" <<'PYEOF'
import sys
import h5py
import numpy as np
sys.path.insert(0, sys.argv[1])
import periodic_crossings as pc
with h5py.File(sys.argv[2], "r") as f:
    t = {k: f["periodic"][k][()] for k in f["periodic"]}
    J, w = pc.body_of(f["parameters"].attrs["scene_toml"])
text = lambda a: np.array([s.decode() if isinstance(s, bytes) else s for s in a])
event, stab, tr = text(t["event"]), text(t["stability"]), t["reduced_trace"]
best = None
for k in np.flatnonzero(event == "fold"):
    fam = t["family"][k]
    rows = np.flatnonzero(t["family"] == fam)
    later = [q for q in rows if q > k and event[q] == "fold"]
    ell = [q for q in rows if q < k and event[q] == "none" and stab[q] == "elliptic"]
    hyp = [q for q in rows if k < q < (later[0] if later else len(tr)) and event[q] == "none"
           and stab[q] == "hyperbolic" and 2 < tr[q] <= 3]
    if hyp and len(ell) >= 2:
        q = min(hyp, key=lambda q: abs(tr[q] - 2.5))
        if best is None or abs(tr[q] - 2.5) < abs(tr[best[0]] - 2.5):
            best = (q, ell)
if best is None:
    sys.exit("paper_periodic: no fold at l = 3 with elliptic orbits before it and a hyperbolic one (2 < tr P <= 3) past it")
r, ell = best
h = float(t["h"][r])
x = lambda r: np.concatenate([t["angular_momentum"][r], t["gamma"][r]])
e = w / np.linalg.norm(w)
a, b = next(((a, b) for a, b in zip(ell[:-1], ell[1:]) if (t["h"][a] - h) * (t["h"][b] - h) <= 0), (ell[-2], ell[-1]))
u = (h - t["h"][a]) / (t["h"][b] - t["h"][a])
xe, Te = (1 - u) * x(a) + u * x(b), (1 - u) * t["period"][a] + u * t["period"][b]
# Each seed with its own number of returns: the orbit's crossings a period in the first one's direction.
seeds, returns = [], []
for x0, T in ((x(r), float(t["period"][r])), (xe, Te)):
    cs, ds = pc.crossings(x0, T, J, w, e, True, directions=True)
    seeds.append(cs[0])
    returns.append(sum(d == ds[0] for d in ds))
with open(sys.argv[3], "w") as f:
    f.write("phi,theta,sheet\n")
    (ph, th, sh), (pe, te, se) = seeds
    for d in (0.01, 0.03, 0.06, 0.1, 0.15):
        f.write("%r,%r,%d\n" % (pe, te + d, se))
    for d in (-0.02, 0.02, 0.005):
        f.write("%r,%r,%d\n" % (ph + d, th, sh))
# The figure's window: about the two orbits' crossings on the hyperbolic one's sheet.
y = lambda ph, th, sh: th if sh > 0 else 2 * np.pi - th
ys = [y(*seeds[0]), y(*seeds[1])] if seeds[1][2] == seeds[0][2] else [y(*seeds[0])]
xs = [seeds[0][0], seeds[1][0]] if seeds[1][2] == seeds[0][2] else [seeds[0][0]]
zoom = "%.3f:%.3f:%.3f:%.3f" % (min(xs) - 0.9, max(xs) + 0.9, min(ys) - 0.6, max(ys) + 0.6)
fold = next(k for k in np.flatnonzero(event == "fold") if t["family"][k] == t["family"][r] and k < r)
with open(sys.argv[3].replace("section_seeds.csv", "fold_pair.txt"), "w") as f:  # for the numbers below
    f.write("%d %d\n" % (t["family"][r], fold))
print(repr(h), *("%r,%r,%d,%d" % (*s, n) for s, n in zip(seeds, returns)), zoom)
PYEOF
) || die "picking the fold pair failed"
read -r hstar seed_hyp seed_ell zoom <<< "$pick"
run poincare --scene "$scene" --l 3 --h "$hstar" --seeds "$p/section_seeds.csv" --t-end "$t_end" --threads 2 \
  --out "$p/section_l3.h5"
run periodic --scene "$scene" --seeds-from-poincare "$p/section_l3.h5" --poincare-point "$seed_hyp" \
  --poincare-point "$seed_ell" --steps 0 --dt 0.01 --manifolds "$points" --manifold-periods "$periods" \
  --manifold-epsilon 1e-3 --out "$p/orbits_l3.h5"
"$PY" -c 'import h5py, sys; s = list(h5py.File(sys.argv[1])["periodic"]["stability"][()]); sys.exit(
    len(s) != 2 or s.count(b"elliptic") != 1)' "$p/orbits_l3.h5" \
  || die "the fold pair at h = $hstar was not found again from its section points (need one elliptic, one hyperbolic orbit)"

# ── figures and numbers ─────────────────────────────────────────────────────
"$PY" "$plots/periodic.py" --out "$figs" "$p/l22.h5" "$p/l3.h5" || die "periodic.py failed"
"$PY" "$plots/poincare.py" --out "$figs" --periodic "$p/orbits_l3.h5" --periodic-h-tol 1e-9 --zoom "$zoom" \
  --dot-size 2 "$p/section_l3.h5" \
  || die "poincare.py failed"
"$PY" - "$plots" "$gen" "$commands" "$p/l22.h5" "$p/l3.h5" "$p/orbits_l3.h5" "$p/fold_pair.txt" "$mode" <<'PYEOF' \
  || die "the periodic numbers failed"
# periodic_numbers.tex (macros for the text), periodic_families.tex (the rows of the families' table)
# and periodic_commands.tex (the runs, verbatim).
import sys
import h5py
import numpy as np

plots, gen, commands, l22, l3, orbits, fold_pair, mode = sys.argv[1:9]
CLASS = {"elliptic": "ell.", "hyperbolic": "hyp.", "inverse_hyperbolic": "inv.\\ hyp.", "complex": "compl."}


def family_rows(t, ell):
    """One table row per family: where it starts, its h and T ranges, the classes along it in order
    (runs of one class; event rows sit on a border), its folds and period doublings, and how many
    sign changes of a bifurcation it saw but did not locate."""
    ev, st, end = text(t["event"]), text(t["stability"]), text(t["family_end"])
    out = []
    for fam in np.unique(t["family"]):
        r = np.flatnonzero(t["family"] == fam)
        start = ("eq.\\ at $h=%.3f$, $\\omega=%.3f$" % (t["h"][r[0]], t["omega"][r[0]]) if t["parent"][r[0]] < 0
                 else f"doubling of {t['parent'][r[0]]} at $h={t['h'][r[0]]:.3f}$")
        runs = [st[q] for q in r if ev[q] == "none"]
        runs = [c for k, c in enumerate(runs) if k == 0 or c != runs[k - 1]]
        missed = end[r[-1]].count("not located")
        classes = " $\\to$ ".join(CLASS[c] for c in runs)
        out.append(f"{ell} & {fam} & {start} & {t['h'][r].min():.3f}--{t['h'][r].max():.3f} & "
                   f"{t['period'][r].min():.2f}--{t['period'][r].max():.2f} & {classes} & "
                   f"{int(np.sum(ev[r] == 'fold'))} & {int(np.sum(ev[r] == 'period_doubling'))} & {missed} "
                   + "\\\\")
    return out


def table(path, group="periodic"):
    with h5py.File(path, "r") as f:
        return {k: f[group][k][()] for k in f[group]}


def text(a):
    return np.array([s.decode() if isinstance(s, bytes) else s for s in a])


# The prose after the table describes the full build's families; a quick build says so.
macros, rows = {"PerQuickNote": "" if mode == "full" else
                " \\textit{(Quick build: short families without their doubled families; the text describes the "
                "full build's.)}"}, []
for name, path in (("A", l22), ("B", l3)):
    t = table(path)
    rows += family_rows(t, f"{t['l'][0]:g}") + (["\\hline"] if name == "A" else [])
    first = t["index"] == 0
    ev = text(t["event"])
    mu = t["multipliers"].reshape(-1, 6, 2)
    z = mu[:, :, 0] + 1j * mu[:, :, 1]
    macros[f"Per{name}Families"] = str(len(np.unique(t["family"])))
    macros[f"Per{name}Orbits"] = str(len(t["h"]))
    macros[f"Per{name}Folds"] = str(int(np.sum(ev == "fold")))
    macros[f"Per{name}Doublings"] = str(int(np.sum(ev == "period_doubling")))
    macros[f"Per{name}FirstPeriod"] = f"{np.max(np.abs(t['period'][first] - 2 * np.pi / t['omega'][first])):.1e}"
    macros[f"Per{name}Residual"] = f"{np.max(t['residual']):.1e}"
    macros[f"Per{name}Product"] = f"{np.max(np.abs(np.prod(z, axis=1) - 1)):.1e}"
    macros[f"Per{name}Missed"] = str(sum(e.count("not located") for e in text(t["family_end"])))
ev = text(t["event"])  # t: l = 3; the family with the most located events:
busy = max(np.unique(t["family"]), key=lambda f: np.sum((t["family"] == f) & (ev != "none")))
macros["PerBBusyFamily"] = str(busy)
macros["PerBBusyEqH"] = f"{t['h'][np.flatnonzero(t['family'] == busy)[0]]:.3f}"
fam, fold = (int(v) for v in open(fold_pair).read().split())
first = np.flatnonzero(t["family"] == fam)[0]
macros["PerSecFamily"] = str(fam)
macros["PerSecEqH"] = f"{t['h'][first]:.3f}"
macros["PerSecFoldH"] = f"{t['h'][fold]:.4f}"
o, m = table(orbits), table(orbits, "manifolds")
hyp = int(np.flatnonzero(text(o["stability"]) != "elliptic")[0])
macros["PerSecH"] = f"{o['h'][hyp]:.6f}"
macros["PerSecHypT"] = f"{o['period'][hyp]:.5f}"
macros["PerSecEllT"] = f"{o['period'][1 - hyp]:.5f}"
macros["PerSecLambda"] = f"{m['multiplier'][0]:.4f}"
macros["PerSecReturns"] = str(int(m["returns"][0]))
macros["PerSecPoints"] = str(len(m["s"]))
with open(f"{gen}/periodic_families.tex", "w") as f:
    f.write("\n".join(rows) + "\n")
with open(f"{gen}/periodic_numbers.tex", "w") as f:
    for k, v in macros.items():
        f.write(f"\\newcommand{{\\{k}}}{{{v}}}\n")
sys.path.insert(0, plots)
from atlas_tables import commands_block  # the same wrapped, pasteable block as the atlas section
open(f"{gen}/periodic_commands.tex", "w").write(commands_block(commands))
PYEOF
