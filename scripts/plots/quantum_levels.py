#!/usr/bin/python3
"""The lowest levels of a quantum top against hbar, from `lgi quantum` files
of one scene at one m, one file per hbar (experiments/QUANTUM.md).

Usage: quantum_levels.py --out DIR [--name NAME] [--levels N] FILE.h5 ...

Draws E_n(hbar) for the lowest N levels (default 12) of each file, joined
across hbar by rank, unconverged levels (converged = 0) as open circles,
with the bottom of the potential min U = -|c| (the `weight` attribute of
/parameters) as a grey line: as hbar -> 0 the levels fall onto it, spaced by
hbar times the frequencies of the hanging equilibrium (docs/quantum.md
section 6). Writes DIR/NAME.{pdf,png} (default NAME: quantum_levels).
"""
import numpy as np

import lgi_plot_common as c


def read(path):
    t = c.load_table(path, "spectrum")
    if t is None:
        c.die(f"{path}: no /spectrum group (give files of lgi quantum)")
    pa = c.load_attrs(path, "parameters")
    weight = np.array([float(x) for x in str(pa.get("weight", "0 0 0")).replace(",", " ").strip("[]() ").split()])
    return {"hbar": float(pa["hbar"]), "energy": t["energy"], "converged": t["converged"] == 1,
            "m": int(t["m"][0]), "scene": c.scene_label(pa), "bottom": -float(np.linalg.norm(weight))}


def main():
    p = c.parser(__doc__.split("\n\n")[0])
    p.add_argument("--name", default="quantum_levels", help="file name of the figure, without extension")
    p.add_argument("--levels", type=int, default=12, help="how many of the lowest levels to draw")
    args = p.parse_args()
    if len(args.files) < 2:
        c.die("give at least two lgi quantum files (one per hbar)")
    runs = sorted((read(f) for f in args.files), key=lambda r: r["hbar"])
    if len({(r["scene"], r["m"]) for r in runs}) != 1:
        c.die("the files must be of one scene at one m")
    fig, ax = c.plt.subplots(figsize=(3.6, 3.0), constrained_layout=True)
    hbar = np.array([r["hbar"] for r in runs])
    n = min(args.levels, min(len(r["energy"]) for r in runs))
    for i in range(n):
        e = np.array([r["energy"][i] for r in runs])
        ok = np.array([r["converged"][i] for r in runs])
        colour = c.plt.get_cmap("viridis")(i / max(n - 1, 1))
        ax.plot(hbar, e, "-", color=colour, lw=0.8)
        ax.plot(hbar[ok], e[ok], "o", ms=3, color=colour)
        ax.plot(hbar[~ok], e[~ok], "o", ms=3, mfc="none", color=colour)
    ax.axhline(runs[0]["bottom"], color="0.5", lw=0.8, ls="--", label="min $U$")
    ax.set_xlim(0, hbar.max() * 1.05)
    ax.set_xlabel("$\\hbar$")
    ax.set_ylabel("$E_n$")
    ax.set_title(f"{runs[0]['scene']}: the lowest {n} levels at $m$ = {runs[0]['m']}", fontsize=9)
    ax.legend(frameon=False, loc="upper left")
    c.save(fig, args.out, args.name)


if __name__ == "__main__":
    main()
